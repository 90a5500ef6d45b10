// SPDX-License-Identifier: MIT
#pragma once

#include <chrono>
#include <cstddef>

namespace smb::cli {

/// True when standard error is a terminal, the only place a progress bar belongs.
[[nodiscard]] bool standard_error_is_terminal();

/// A one-line progress bar redrawn in place on standard error. Hand-written because Debian
/// packages no C++ progress-bar library and this needs nothing beyond a carriage return.
/// Disabled, it draws nothing at all.
class ProgressBar {
public:
    ProgressBar(std::size_t total, bool enabled);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// Records that `done` of the total are finished; redraws at most ten times a second.
    void update(std::size_t done, double last_step_seconds);
    /// Erases the bar, leaving the terminal line clean for the summary.
    void finish();

private:
    void draw(std::size_t done, double last_step_seconds);

    std::size_t total_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace smb::cli
