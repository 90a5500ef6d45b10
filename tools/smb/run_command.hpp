// SPDX-License-Identifier: MIT
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "environment_options.hpp"

namespace smb::cli {

/// `smb run`: the paper's dynamic environment in memory, detected step after step by one World,
/// timed, and checked against the independent grid reference.
class RunCommand {
public:
    explicit RunCommand(CLI::App& parent);

    [[nodiscard]] bool selected() const { return app_->parsed(); }
    /// exit_status::success, or exit_status::mismatch when a checked step differs from the
    /// reference.
    [[nodiscard]] int run() const;

private:
    template <int Dim>
    int run_in() const;

    CLI::App* app_;
    EnvironmentOptions environment_;
    std::size_t target_cell_population_ = 0;
    std::size_t threads_ = 1;
    std::string pipeline_ = "persistent";
    std::string segment_rule_ = "count";
    double skin_ = 0;
    std::size_t check_every_ = 0;
    bool no_check_ = false;
    bool json_ = false;
    bool no_progress_ = false;
    std::string pair_counts_;
    bool distributed_ = false;
};

}  // namespace smb::cli
