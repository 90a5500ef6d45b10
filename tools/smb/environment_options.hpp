// SPDX-License-Identifier: MIT
#pragma once
// The options that describe the paper's dynamic environment, shared by `smb generate` and
// `smb run`.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>

#include "smb/workload/dynamic_environment.hpp"

namespace smb::cli {

struct EnvironmentOptions {
    int dimension = 3;
    std::size_t box_count = 200000;
    double packing_density = 0.4;
    double cube_side = 0;  ///< used when --side was given
    double size_ratio = 2.5;
    double update_factor = 1e-3;
    std::size_t steps = 100;
    std::uint64_t seed = 1;

    CLI::Option* side_option = nullptr;

    /// The environment's parameters; throws std::invalid_argument when the cube would be narrower
    /// than the largest box.
    [[nodiscard]] workload::EnvironmentParams params() const;

private:
    void check_cube_side() const;
};

/// Adds --dim, -n, --density | --side, --size-ratio, --update-factor, --steps and --seed to
/// `command`, with the defaults already in `options`.
void add_environment_options(CLI::App& command, EnvironmentOptions& options);

}  // namespace smb::cli
