// SPDX-License-Identifier: MIT
#pragma once
// Float copies of boxes that bound them, and an overlap test on them that is exact or says it
// cannot tell. The statics a moving box caches are tested at every step: as 2 * Dim floats a
// static is 24 bytes (3D) where a Box<double, 3> is 48, and its test is two vector compares
// (GCC vector extensions, SSE on the baseline x86-64) instead of twelve scalar ones.
//
// A copy is rounded outward (min down, max up), a tested box inward: a float test that fails is
// then a certain miss, one that passes with room to spare on every axis a certain hit, and only
// a boundary that falls within one float of the other's (rare) needs the exact boxes. A copy
// holds (min, -max) and a tested box (max, -min), so that every lane asks the same question,
// copy <= box: min_k <= box.max_k, and -max_k <= -box.min_k (negation is exact).

#include <array>
#include <bit>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <limits>

#include "cuts/float_lanes.hpp"
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

/// A box as 2 * Dim floats in one of the two layouts above.
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

/// The tested box: (down(max), -up(min)), which it contains.
template <std::floating_point Real, int Dim>
[[nodiscard]] FloatBox<Dim> inward_query(const Box<Real, Dim>& box) noexcept {
    FloatBox<Dim> f;
    for (int k = 0; k < Dim; ++k) {
        f.v[k] = float_down(box.max[k]);
        f.v[Dim + k] = -float_up(box.min[k]);
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

/// Compares the outward copy s of a box S with the inward query q of a box Q (closed overlap):
/// bit 0 of the result is set when they may overlap (clear: certainly not), bit 1 when they
/// certainly do. Why: s.min = down(S.min) is at most S.min, and S.min is below the float after
/// s.min; q.max = down(Q.max) is the largest float at most Q.max. So S.min <= Q.max implies
/// s.min <= q.max, and s.min < q.max (floats) implies S.min < next(s.min) <= q.max <= Q.max;
/// the same on the other side and every axis. No branch: a quarter of the cached statics
/// overlap, too many for a branch to be predicted.
class FloatOverlap {
public:
    template <int Dim>
    explicit FloatOverlap(const FloatBox<Dim>& q) noexcept {
        static_assert(Dim == 2 || Dim == 3);
        std::memcpy(&low_, q.v.data(), sizeof(Floats));
        std::memcpy(&high_, q.v.data() + (2 * Dim - 4), sizeof(Floats));
    }

    /// Lanes 0..3 and 2 * Dim - 4 .. 2 * Dim - 1 cover the 2 * Dim floats (overlapping in 3D).
    template <int Dim>
    [[nodiscard]] unsigned test(const FloatBox<Dim>& s) const noexcept {
        Floats low;
        Floats high;
        std::memcpy(&low, s.v.data(), sizeof(Floats));
        std::memcpy(&high, s.v.data() + (2 * Dim - 4), sizeof(Floats));
        const Masks maybe = (low <= low_) & (high <= high_);
        const Masks surely = (low < low_) & (high < high_);
        return static_cast<unsigned>(all(maybe)) | static_cast<unsigned>(all(surely)) << 1;
    }

private:
    using Floats = FloatLanes<4>::Floats;
    using Masks = FloatLanes<4>::Masks;

    [[nodiscard]] static bool all(const Masks& m) noexcept { return lane_bits<4>(m) == 0xFU; }

    Floats low_;
    Floats high_;
};

}  // namespace smb::detail
