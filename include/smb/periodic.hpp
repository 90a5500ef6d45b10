// SPDX-License-Identifier: MIT
#pragma once
// Periodic domains: axes on which space wraps around, and the pairs found across them
// (docs/periodic.md).

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb {

/// Which axes wrap around, and where. On a periodic axis k, space repeats with the period
/// P_k = hi[k] - lo[k] (computed in double): a box and its images translated by any integer
/// multiple of P_k are the same box. The other axes are ordinary (lo and hi are not read).
///
/// What a box may be, on a periodic axis: anywhere (a particle's centre wrapped into
/// [lo, hi), its box sticking out of it on either side, or a box several periods away, up to
/// kMaxPeriodsAway), as long as its extent max - min is below half the period
/// (2 (max - min) < P_k in double). Then two boxes meet in at most one image, so the shift of a
/// pair is unique. A box that breaks this is rejected with InvalidBoxError.
template <std::floating_point Real, int Dim>
struct PeriodicDomain {
    /// How far from [lo, hi) a box may lie, in periods: the shifts are 32-bit integers, and
    /// the translations by them stay exact to far below the period.
    static constexpr double kMaxPeriodsAway = 1 << 20;

    std::array<bool, Dim> periodic{};
    std::array<Real, Dim> lo{};
    std::array<Real, Dim> hi{};

    /// Makes axis k periodic over [lo, hi).
    PeriodicDomain& wrap(int k, Real axis_lo, Real axis_hi) {
        periodic[static_cast<std::size_t>(k)] = true;
        lo[static_cast<std::size_t>(k)] = axis_lo;
        hi[static_cast<std::size_t>(k)] = axis_hi;
        return *this;
    }
    [[nodiscard]] bool any_periodic() const noexcept {
        return std::find(periodic.begin(), periodic.end(), true) != periodic.end();
    }
    /// The period of axis k, in double: every translation is computed from it.
    [[nodiscard]] double period(int k) const noexcept {
        return static_cast<double>(hi[static_cast<std::size_t>(k)]) -
               static_cast<double>(lo[static_cast<std::size_t>(k)]);
    }
};

using PeriodicDomain2f = PeriodicDomain<float, 2>;
using PeriodicDomain2d = PeriodicDomain<double, 2>;
using PeriodicDomain3f = PeriodicDomain<float, 3>;
using PeriodicDomain3d = PeriodicDomain<double, 3>;

/// A pair of boxes that overlap in a periodic domain: box a overlaps box b translated by
/// shift[k] periods on every axis k (see overlaps_with_shift). a < b. shift[k] is 0 on an axis
/// that is not periodic, and beyond the dimension (shift[2] in 2D). Where every box's min lies
/// in [lo, hi) on a periodic axis (a wrapped particle whose box sticks out of the domain by
/// less than half a period), the shift on it is -1, 0 or +1. Each pair is reported once: where
/// the rounding of the translation lets it pass under two neighbouring shifts (both extents
/// within a few rounding steps of half the period), the one nearer 0 on every axis is reported.
struct PeriodicPair {
    BoxId a = 0;
    BoxId b = 0;
    std::array<std::int32_t, 3> shift{};

    friend bool operator==(const PeriodicPair&, const PeriodicPair&) = default;
};

/// Orders periodic pairs by (a, b, shift): the pair CSV's order.
inline void sort_periodic_pairs(std::vector<PeriodicPair>& pairs) {
    std::sort(pairs.begin(), pairs.end(), [](const PeriodicPair& x, const PeriodicPair& y) {
        return std::tie(x.a, x.b, x.shift) < std::tie(y.a, y.b, y.shift);
    });
}

namespace detail {
/// A bound in a message: the shortest text that reads back to the same value.
template <std::floating_point Real>
[[nodiscard]] std::string bound_text(Real value) {
    char text[64];
    const std::to_chars_result written = std::to_chars(text, text + sizeof text, value);
    return std::string(text, written.ptr);
}
}  // namespace detail

/// Throws ArgumentError unless every periodic axis has finite lo < hi, with a period that is
/// finite and not zero in double.
template <std::floating_point Real, int Dim>
void check_domain(const PeriodicDomain<Real, Dim>& domain) {
    for (int k = 0; k < Dim; ++k) {
        if (!domain.periodic[static_cast<std::size_t>(k)]) continue;
        const Real lo = domain.lo[static_cast<std::size_t>(k)];
        const Real hi = domain.hi[static_cast<std::size_t>(k)];
        const std::string interval = "periodic domain: the " + std::string(1, "xyz"[k]) + " interval [" +
                                     detail::bound_text(lo) + ", " + detail::bound_text(hi) + ")";
        if (!std::isfinite(lo) || !std::isfinite(hi)) throw ArgumentError(interval + " has a NaN or infinite bound");
        if (!(lo < hi)) throw ArgumentError(interval + " is empty (lo must be below hi)");
        if (!std::isfinite(domain.period(k)))
            throw ArgumentError(interval + " is too wide: its period hi - lo overflows a double");
    }
}

/// The relation a periodic detection reports: box a overlaps box b translated by `shift`
/// periods, closed, on every axis. On a periodic axis k, with t = shift[k] * P_k, it is
/// a.min[k] <= b.max[k] + t and b.min[k] + t <= a.max[k], every operation in double (the
/// translation rounds, and this is how it rounds); on another axis, shift[k] must be 0 and the
/// test is smb::overlaps'. A pair (a, b) is always tested with b the box of the larger name.
template <std::floating_point Real, int Dim>
[[nodiscard]] bool overlaps_with_shift(const Box<Real, Dim>& a, const Box<Real, Dim>& b,
                                       const std::array<std::int32_t, 3>& shift,
                                       const PeriodicDomain<Real, Dim>& domain) noexcept {
    for (int k = 0; k < Dim; ++k) {
        const auto ks = static_cast<std::size_t>(k);
        if (!domain.periodic[ks]) {
            if (shift[ks] != 0 || !(a.min[ks] <= b.max[ks] && b.min[ks] <= a.max[ks])) return false;
            continue;
        }
        const double t = static_cast<double>(shift[ks]) * domain.period(k);
        if (!(static_cast<double>(a.min[ks]) <= static_cast<double>(b.max[ks]) + t &&
              static_cast<double>(b.min[ks]) + t <= static_cast<double>(a.max[ks])))
            return false;
    }
    return true;
}

}  // namespace smb
