// SPDX-License-Identifier: MIT
#pragma once
// The seconds a phase of a detection takes, as DetectStats and DetectProfile report them. A
// watch made stopped (a detection without DetectionSettings::profile) never reads the clock.

#include <chrono>

namespace smb::detail {

class Stopwatch {
public:
    explicit Stopwatch(bool running = true) noexcept : start_(running ? Clock::now() : Clock::time_point{}) {}

    /// Seconds since the watch started (or last lapped); zero where it was made stopped.
    [[nodiscard]] double seconds() const noexcept {
        return start_ == Clock::time_point{} ? 0.0 : std::chrono::duration<double>(Clock::now() - start_).count();
    }

    /// Seconds since the watch started (or last lapped), and starts it again from now: the phases
    /// of a sequence, one after the other, with no gap between them.
    double lap() noexcept {
        if (start_ == Clock::time_point{}) return 0.0;
        const Clock::time_point now = Clock::now();
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return elapsed;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;  // the epoch: stopped
};

}  // namespace smb::detail
