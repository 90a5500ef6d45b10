// SPDX-License-Identifier: MIT
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace smb::cli {

/// `smb pairs`: the overlapping pairs of every frame of a scene CSV, as a pair CSV, or with
/// --events the pairs that begin and end overlapping, as an event CSV.
class PairsCommand {
public:
    explicit PairsCommand(CLI::App& parent);

    [[nodiscard]] bool selected() const { return app_->parsed(); }
    /// Returns the exit status; throws on bad input or I/O failure.
    [[nodiscard]] int run() const;

private:
    CLI::App* app_;
    std::string input_ = "-";
    std::string output_ = "-";
    std::size_t pairs_in_memory_ = std::size_t{1} << 24;  ///< 256 MiB of pairs
    bool events_ = false;                                 ///< the event CSV instead of the pair CSV
    std::string periodic_;                                ///< --periodic X0:X1,Y0:Y1[,Z0:Z1]: the periodic pair CSV
    bool distributed_ = false;                            ///< --distributed: over the MPI ranks (smb::mpi)
};

}  // namespace smb::cli
