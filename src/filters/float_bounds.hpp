// SPDX-License-Identifier: MIT
#pragma once
// Float boxes that bound a box (its outward copy: min rounded down, max rounded up), and
// whether a box lies inside one. A moving box's fat box (static_contacts.hpp) is such a copy:
// the region the statics' grid is asked for and the box is kept inside of, the same region
// exactly, and the span of the lattice its cached statics are held on (quantized_bounds.hpp).
// A copy holds (min, -max), so that one comparison direction serves both sides of an axis.

#include <array>
#include <bit>
#include <concepts>
#include <cstdint>
#include <limits>

#include "smb/box.hpp"

namespace smb::detail {

/// The largest float at most x (x finite or infinite, never NaN). Written without converting
/// an out-of-range value to float, which is undefined, and without a branch on the rounding
/// (which way the nearest float lies is a coin toss: six a moving box a step).
template <std::floating_point Real>
[[nodiscard]] inline float float_down(Real x) noexcept {
    constexpr float kTop = std::numeric_limits<float>::max();
    if constexpr (std::same_as<Real, float>) {
        return x;
    } else {
        if (x > static_cast<Real>(kTop)) return kTop;
        if (x < static_cast<Real>(-kTop)) return -std::numeric_limits<float>::infinity();
        const auto f = static_cast<float>(x);
        // The float's bits as an integer in the floats' order (negative floats reflected), one
        // step down where the nearest float is above x. f = +0 is never above x (a negative x
        // rounds to -0), and -0 steps to the negative float nearest zero.
        const auto bits = std::bit_cast<std::int32_t>(f);
        const std::int32_t key = bits ^ ((bits >> 31) & 0x7FFFFFFF);
        const std::int32_t down = key - static_cast<std::int32_t>(static_cast<Real>(f) > x);
        return std::bit_cast<float>(down ^ ((down >> 31) & 0x7FFFFFFF));
    }
}

/// The smallest float at least x.
template <std::floating_point Real>
[[nodiscard]] inline float float_up(Real x) noexcept {
    return -float_down<Real>(-x);
}

/// A box as 2 * Dim floats: (min, -max).
template <int Dim>
struct FloatBox {
    std::array<float, 2 * Dim> v{};
};

/// The copy of a static: (down(min), -up(max)), which contains the box.
template <std::floating_point Real, int Dim>
[[nodiscard]] FloatBox<Dim> outward_copy(const Box<Real, Dim>& box) noexcept {
    FloatBox<Dim> f;
    for (int k = 0; k < Dim; ++k) {
        f.v[k] = float_down(box.min[k]);
        f.v[Dim + k] = -float_up(box.max[k]);
    }
    return f;
}

/// The Real box an outward copy stands for (every float is a Real exactly).
template <std::floating_point Real, int Dim>
[[nodiscard]] Box<Real, Dim> widened(const FloatBox<Dim>& f) noexcept {
    Box<Real, Dim> box;
    for (int k = 0; k < Dim; ++k) {
        box.min[k] = static_cast<Real>(f.v[k]);
        box.max[k] = -static_cast<Real>(f.v[Dim + k]);
    }
    return box;
}

/// Whether `box` lies inside the region the outward copy f stands for (compared as Real, where
/// every float is exact).
template <std::floating_point Real, int Dim>
[[nodiscard]] inline bool inside(const Box<Real, Dim>& box, const FloatBox<Dim>& f) noexcept {
    int in = 1;
    for (int k = 0; k < Dim; ++k) {
        in &= static_cast<int>(box.min[k] >= static_cast<Real>(f.v[k])) &
              static_cast<int>(-box.max[k] >= static_cast<Real>(f.v[Dim + k]));
    }
    return in != 0;
}

}  // namespace smb::detail
