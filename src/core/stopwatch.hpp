// SPDX-License-Identifier: MIT
#pragma once
// The seconds a phase of a detection takes, as DetectStats reports them.

#include <chrono>

namespace smb::detail {

class Stopwatch {
public:
    Stopwatch() noexcept : start_(Clock::now()) {}

    /// Seconds since the watch started (or last lapped).
    [[nodiscard]] double seconds() const noexcept {
        return std::chrono::duration<double>(Clock::now() - start_).count();
    }

    /// Seconds since the watch started (or last lapped), and starts it again from now: the phases
    /// of a sequence, one after the other, with no gap between them.
    double lap() noexcept {
        const Clock::time_point now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return elapsed;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

}  // namespace smb::detail
