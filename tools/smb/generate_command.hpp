// SPDX-License-Identifier: MIT
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "environment_options.hpp"

namespace smb::cli {

/// `smb generate`: writes the paper's dynamic environment as a scene CSV, one frame per step.
class GenerateCommand {
public:
    explicit GenerateCommand(CLI::App& parent);

    [[nodiscard]] bool selected() const { return app_->parsed(); }
    [[nodiscard]] int run() const;

private:
    CLI::App* app_;
    EnvironmentOptions environment_;
    std::string output_ = "-";
};

}  // namespace smb::cli
