#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace smb::cli {

/// `smb pairs`: the overlapping pairs of every frame of a scene CSV, as a pair CSV.
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
};

}  // namespace smb::cli
