// SPDX-License-Identifier: MIT
#pragma once
// The boxes a Detector holds for itself: the caller's double boxes as floats, shifted by an
// origin (the middle of the scene) and rounded to the nearest float. Half the bytes of a double
// copy, and every pass over them reads half as much memory; exactness is kept by testing again,
// on the caller's own boxes, every pair the floats cannot settle.
//
// Why the floats lose no pair: held(x) = nearest float to fl(x - origin), clamped to the finite
// floats, never decreases as x grows (each step rounds monotonically). So a.min <= b.max gives
// held(a.min) <= held(b.max): boxes that overlap hold boxes that overlap. The converse can fail
// only where a comparison is within rounding, which surely_overlap() detects (see there).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "smb/box.hpp"

namespace smb::detail {

/// A float box from +infinity to -infinity on every axis: it overlaps no box, itself included,
/// and on no axis does it reach a box, or a box reach it, from either side. Bullet's destroyed
/// proxies and the skin list's vacant positions (skin/candidate_list.hpp) hold it.
template <int Dim>
[[nodiscard]] inline Box<float, Dim> empty_float_box() noexcept {
    Box<float, Dim> empty;
    empty.min.fill(std::numeric_limits<float>::infinity());
    empty.max.fill(-std::numeric_limits<float>::infinity());
    return empty;
}

/// The nearest float to `value`, or the largest finite float of its sign beyond their range
/// (where a plain conversion would be undefined).
template <std::floating_point Input>
[[nodiscard]] inline float clamped_float(Input value) noexcept {
    constexpr auto top = static_cast<Input>(std::numeric_limits<float>::max());
    return static_cast<float>(std::clamp(value, -top, top));
}

/// The held copy of `box`: shifted by `origin` and rounded to floats.
template <std::floating_point Input, int Dim>
[[nodiscard]] inline Box<float, Dim> held_box(const Box<Input, Dim>& box,
                                              const std::array<Input, Dim>& origin) noexcept {
    Box<float, Dim> held;
    for (int k = 0; k < Dim; ++k) {
        held.min[k] = clamped_float(box.min[k] - origin[k]);
        held.max[k] = clamped_float(box.max[k] - origin[k]);
    }
    return held;
}

/// `box` as a pipeline of Real holds it: the box itself where Real is the input's type (the
/// origin is then zero), its held copy otherwise.
template <std::floating_point Real, std::floating_point Input, int Dim>
[[nodiscard]] inline Box<Real, Dim> held_as(const Box<Input, Dim>& box,
                                            const std::type_identity_t<std::array<Input, Dim>>& origin) noexcept {
    if constexpr (std::is_same_v<Real, Input>) {
        (void)origin;
        return box;
    } else {
        return held_box<Input, Dim>(box, origin);
    }
}

/// `value` rounded down (or up) to a float, clamped to the finite floats.
[[nodiscard]] inline float float_below(double value) noexcept {
    constexpr double top = std::numeric_limits<float>::max();
    const double clamped = std::clamp(value, -top, top);
    auto rounded = static_cast<float>(clamped);
    if (static_cast<double>(rounded) > clamped) rounded = std::nextafter(rounded, -std::numeric_limits<float>::max());
    return rounded;
}
[[nodiscard]] inline float float_above(double value) noexcept { return -float_below(-value); }

/// The least float difference of two held coordinates that proves the order of the input
/// coordinates they hold, for a scene within [lo, hi] held from `origin`. A held coordinate h
/// of shifted coordinate v = fl(x - origin), |v| <= M, is within ulp(M) / 2 <= 2^-24 M (plus
/// half the smallest subnormal) of v. Where the float difference of two held coordinates is at
/// least M 2^-21 (plus 2^-140), their exact difference exceeds both errors together, so the
/// shifted coordinates are in the same order, and the inputs too (the shift is monotone): held
/// boxes that overlap by that margin on every axis hold input boxes that overlap.
template <std::floating_point Input, int Dim>
[[nodiscard]] float held_sure_margin(const std::array<Input, Dim>& origin, const std::array<Input, Dim>& lo,
                                     const std::array<Input, Dim>& hi) noexcept {
    double largest = 0;
    for (int k = 0; k < Dim; ++k) {
        largest = std::max(largest, std::abs(static_cast<double>(lo[k] - origin[k])));
        largest = std::max(largest, std::abs(static_cast<double>(hi[k] - origin[k])));
    }
    return float_above(std::ldexp(largest, -21) + std::ldexp(1.0, -140));
}

/// A key per float that grows by one from each float to the next (and from -0 to +0).
[[nodiscard]] inline std::int64_t float_step_key(float value) noexcept {
    const auto bits = std::bit_cast<std::uint32_t>(value);
    return (bits & 0x80000000U) != 0 ? std::int64_t{0x7FFFFFFF} - (bits & 0x7FFFFFFFU)
                                     : std::int64_t{0x80000000} + bits;
}

/// True when held boxes `a` and `b` prove that the boxes they hold overlap. A held coordinate h
/// of a shifted coordinate v (nearest, or clamped beyond the float range) has
/// next_down(h) < v < next_up(h). Four steps apart (two would do but for -0 and +0, which are
/// two steps and one value), next_up(held a.min) <= next_down(held b.max), so shifted a.min <
/// shifted b.max and, the shift being monotone, a.min <= b.max. Pairs closer than that
/// (touching, or within a few floats) go to the exact test.
[[nodiscard]] inline bool surely_below(float low, float high) noexcept {
    return float_step_key(high) - float_step_key(low) >= 4;
}
template <int Dim>
[[nodiscard]] inline bool surely_overlap(const Box<float, Dim>& a, const Box<float, Dim>& b) noexcept {
    for (int k = 0; k < Dim; ++k) {
        if (!surely_below(a.min[k], b.max[k]) || !surely_below(b.min[k], a.max[k])) return false;
    }
    return true;
}

}  // namespace smb::detail
