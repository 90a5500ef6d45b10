// SPDX-License-Identifier: MIT
#include "progress_bar.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <string>

namespace smb::cli {

namespace {

constexpr int bar_width = 30;
constexpr auto redraw_interval = std::chrono::milliseconds(100);

}  // namespace

bool standard_error_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(std::size_t total, bool enabled) : total_(total), enabled_(enabled) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(std::size_t done, double last_step_seconds) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && done < total_ && now - last_draw_ < redraw_interval) return;
    last_draw_ = now;
    draw(done, last_step_seconds);
}

void ProgressBar::draw(std::size_t done, double last_step_seconds) {
    const auto filled = total_ == 0 ? bar_width : static_cast<int>(done * bar_width / total_);
    const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                            std::string(static_cast<std::size_t>(bar_width - filled), '.');
    std::fputs(fmt::format("\r[{}] {}/{} {}, last {:.3f} s ", bar, done, total_, total_ == 1 ? "step" : "steps",
                           last_step_seconds)
                   .c_str(),
               stderr);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (!enabled_ || !drawn_) return;
    std::fputs(fmt::format("\r{:{}}\r", "", bar_width + 40).c_str(), stderr);
    std::fflush(stderr);
    drawn_ = false;
}

}  // namespace smb::cli
