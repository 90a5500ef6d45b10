// SPDX-License-Identifier: MIT
#pragma once
// The cell check's keys: coordinates as floats, and as 32-bit keys whose unsigned order is the
// coordinates' order, for the sort on x of a crowded cell.

#include <bit>
#include <concepts>
#include <cstdint>
#include <type_traits>

#include "core/held_box.hpp"

namespace smb::detail {

/// `value` as a float: itself, or clamped_float() of a double. Rounding never reverses an
/// order: x <= y gives to_float(x) <= to_float(y), which is all the cell check asks of it.
template <std::floating_point Real>
[[nodiscard]] inline float to_float(Real value) noexcept {
    if constexpr (std::is_same_v<Real, float>) {
        return value;
    } else {
        return clamped_float(value);
    }
}

/// A 32-bit key that never decreases as `value` grows: `value` rounded down to float, with -0
/// made +0 (they are equal coordinates), mapped so that unsigned order is numeric order.
template <std::floating_point Real>
[[nodiscard]] inline std::uint32_t monotone_key(Real value) noexcept {
    const float rounded = to_float(value) + 0.0F;  // -0 + 0 = +0
    const auto bits = std::bit_cast<std::uint32_t>(rounded);
    std::uint32_t key = (bits & 0x80000000U) != 0 ? ~bits : bits | 0x80000000U;
    if constexpr (!std::is_same_v<Real, float>) {
        // Rounded up: the next key down is the next float down (never below -inf's key).
        key -= static_cast<Real>(rounded) > value ? 1U : 0U;
    }
    return key;
}

/// The float whose monotone_key() is `key`: for float input the value itself, for double input
/// the float at or below it.
[[nodiscard]] inline float float_of_key(std::uint32_t key) noexcept {
    return std::bit_cast<float>((key & 0x80000000U) != 0 ? key & 0x7FFFFFFFU : ~key);
}

}  // namespace smb::detail
