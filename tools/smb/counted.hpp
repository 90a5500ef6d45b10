// SPDX-License-Identifier: MIT
#pragma once
// A count and its noun for messages: "1 frame", "0 frames", "2 boxes". The plural is used for
// every count but exactly one.

#include <fmt/format.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace smb::cli {

/// `count` and `singular`, or `plural` unless `count` is 1.
[[nodiscard]] inline std::string counted(std::uint64_t count, std::string_view singular, std::string_view plural) {
    return fmt::format("{} {}", count, count == 1 ? singular : plural);
}

/// `count` and `noun`, with an "s" unless `count` is 1.
[[nodiscard]] inline std::string counted(std::uint64_t count, std::string_view noun) {
    return count == 1 ? fmt::format("1 {}", noun) : fmt::format("{} {}s", count, noun);
}

}  // namespace smb::cli
