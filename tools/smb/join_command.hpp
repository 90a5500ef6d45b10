// SPDX-License-Identifier: MIT
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace smb::cli {

/// `smb join`: the overlapping pairs between the boxes of two scene CSVs, frame by frame, as a
/// join CSV (`frame,left,right`).
class JoinCommand {
public:
    explicit JoinCommand(CLI::App& parent);

    [[nodiscard]] bool selected() const { return app_->parsed(); }
    /// Returns the exit status; throws on bad input or I/O failure.
    [[nodiscard]] int run() const;

private:
    CLI::App* app_;
    std::string left_;
    std::string right_;
    std::string output_ = "-";
    std::size_t pairs_in_memory_ = std::size_t{1} << 24;  ///< 256 MiB of pairs
};

}  // namespace smb::cli
