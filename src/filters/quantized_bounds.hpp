// SPDX-License-Identifier: MIT
#pragma once
// The bounds of a moving box's cache of statics (static_contacts.hpp). Its fat box is an outward
// float copy of a box (min rounded down, max rounded up): the region the statics' grid is asked
// for and the box is kept inside of, the same region exactly, and the span of a lattice on which
// the cached statics are held as 16-bit integers, with an overlap test on them that is exact or
// says it cannot tell. The cache is read at every step and its reading is bound by memory: a
// static as 2 * Dim 16-bit values is 12 bytes (3D), half its 24 bytes as floats, and its test one
// vector compare of 8 lanes. Both copies hold (min, -max), so that one comparison direction
// serves both sides of an axis.
//
// Exactness rests on one property only: the map q from a coordinate to its lattice value never
// decreases (x <= y gives q(x) <= q(y)). The map is (x - origin) * scale in double, clamped to
// [0, kTop] and truncated: every step of it is monotone (a correctly rounded subtraction or
// product by a positive constant, a clamp, a truncation of a value at least 0). Then, for two
// faces x and y, x <= y gives q(x) <= q(y), and q(x) < q(y) gives x < y; q(x) == q(y) cannot
// tell. A copy holds (q(min), -q(max)) and a tested box (q(max), -q(min)), so that every lane
// asks copy <= box: all lanes strictly below is a certain hit, any lane above a certain miss, and
// the rest (faces within one lattice step of each other: a step is the fat box's side over
// 32767, so this is rare) is decided on the exact boxes. The origin and scale matter only for how
// often the test cannot tell, never for its answers; a fat box with no finite, positive extent on
// an axis maps every value on it to 0 (the test cannot tell there).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/tuning.hpp"
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

/// A box's 2 * Dim lattice values, in one of the two layouts above.
template <int Dim>
using QuantBox = std::array<std::int16_t, 2 * Dim>;

/// The lattice over one fat box (an outward float copy), with the scales
/// scales(fat) chose for it (kept beside the fat box, so that a step does not divide again).
template <int Dim>
class Lattice {
public:
    static constexpr double kTop = tuning::static_lattice_top;

    /// Lattice steps per unit on each axis: kTop over the fat box's side, as a float (any
    /// positive value serves, the same for the copies and the tested box).
    [[nodiscard]] static std::array<float, Dim> scales(const FloatBox<Dim>& fat) noexcept {
        std::array<float, Dim> scale{};
        for (int k = 0; k < Dim; ++k) {
            const double range = -static_cast<double>(fat.v[Dim + k]) - static_cast<double>(fat.v[k]);
            const auto s = static_cast<float>(std::min(kTop / range, 1e30));
            scale[k] = range > 0 && std::isfinite(range) && s > 0 ? s : 0;
        }
        return scale;
    }

    Lattice(const FloatBox<Dim>& fat, const std::array<float, Dim>& scale) noexcept {
        for (int k = 0; k < Dim; ++k) {
            origin_[k] = static_cast<double>(fat.v[k]);
            scale_[k] = static_cast<double>(scale[k]);
        }
    }

    /// q(x) on axis k. A NaN product (an infinite difference times a scale of 0) maps to 0, as
    /// every other value does on such an axis.
    template <std::floating_point Real>
    [[nodiscard]] std::int16_t value(int k, Real x) const noexcept {
        const double t = (static_cast<double>(x) - origin_[k]) * scale_[k];
        const double clamped = t > 0 ? (t < kTop ? t : kTop) : 0;
        return static_cast<std::int16_t>(clamped);
    }

    /// A cached static: (q(min), -q(max)).
    template <std::floating_point Real>
    [[nodiscard]] QuantBox<Dim> copy(const Box<Real, Dim>& box) const noexcept {
        return packed(box.min, box.max);
    }

    /// A tested box: (q(max), -q(min)).
    template <std::floating_point Real>
    [[nodiscard]] QuantBox<Dim> query(const Box<Real, Dim>& box) const noexcept {
        return packed(box.max, box.min);
    }

private:
    /// (q(first), -q(second)), axis by axis.
    template <class Corner>
    [[nodiscard]] QuantBox<Dim> packed(const Corner& first, const Corner& second) const noexcept {
        QuantBox<Dim> q;
        for (int k = 0; k < Dim; ++k) {
            q[k] = value(k, first[k]);
            q[Dim + k] = static_cast<std::int16_t>(-value(k, second[k]));
        }
        return q;
    }

    std::array<double, Dim> origin_{};
    std::array<double, Dim> scale_{};
};

/// Tests copies against one tested box, eight 16-bit lanes at once. A copy is read as 16 bytes
/// from its first value (whatever lies after it in memory, which must be readable), and the
/// lanes past 2 * Dim are made to pass.
template <int Dim>
class QuantOverlap {
public:
    static_assert(Dim == 2 || Dim == 3);

    explicit QuantOverlap(const QuantBox<Dim>& q) noexcept {
        // Built as one vector (lane by lane through memory, it stalled the first test).
        constexpr std::int16_t kMax = std::numeric_limits<std::int16_t>::max();
        constexpr std::int16_t kMin = std::numeric_limits<std::int16_t>::min();
        if constexpr (Dim == 3) {
            query_ = Shorts{q[0], q[1], q[2], q[3], q[4], q[5], kMax, kMax};
            used_ = Shorts{-1, -1, -1, -1, -1, -1, 0, 0};
            unused_low_ = Shorts{0, 0, 0, 0, 0, 0, kMin, kMin};
        } else {
            query_ = Shorts{q[0], q[1], q[2], q[3], kMax, kMax, kMax, kMax};
            used_ = Shorts{-1, -1, -1, -1, 0, 0, 0, 0};
            unused_low_ = Shorts{0, 0, 0, 0, kMin, kMin, kMin, kMin};
        }
    }

    /// Bit 0 of the result: they may overlap (clear: certainly not); bit 1: they certainly do.
    /// `copy` points to a copy followed by 16 - sizeof(QuantBox<Dim>) readable bytes.
    [[nodiscard]] unsigned test(const void* copy) const noexcept {
        Shorts s;
        std::memcpy(&s, copy, sizeof(Shorts));
        s = (s & used_) | unused_low_;
        const Shorts maybe = s <= query_;
        const Shorts surely = s < query_;
        return static_cast<unsigned>(all(maybe)) | static_cast<unsigned>(all(surely)) << 1;
    }

private:
    using Shorts [[gnu::vector_size(16)]] = std::int16_t;

    [[nodiscard]] static bool all(const Shorts& m) noexcept {
#if defined(__x86_64__) && defined(__GNUC__)
        using Bytes [[gnu::vector_size(16)]] = char;
        return __builtin_ia32_pmovmskb128(__builtin_bit_cast(Bytes, m)) == 0xFFFF;
#else
        bool every = true;
        for (int lane = 0; lane < 8; ++lane) every = every && m[lane] != 0;
        return every;
#endif
    }

    Shorts query_{};
    Shorts used_{};        // all ones in the lanes a copy fills
    Shorts unused_low_{};  // the lowest value in the others, below any query lane
};

}  // namespace smb::detail
