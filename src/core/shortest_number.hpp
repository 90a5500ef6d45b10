// SPDX-License-Identifier: MIT
#pragma once
// Numbers in error messages as the caller would write them: the shortest text that reads back to
// the same value (0.1, not 0.100000 or 0.10000000000000001).

#include <charconv>
#include <concepts>
#include <string>

namespace smb::detail {

template <std::floating_point Real>
[[nodiscard]] std::string shortest_number(Real value) {
    char text[64];
    const std::to_chars_result written = std::to_chars(text, text + sizeof text, value);
    return std::string(text, written.ptr);
}

}  // namespace smb::detail
