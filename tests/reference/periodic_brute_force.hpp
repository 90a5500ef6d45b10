// SPDX-License-Identifier: MIT
#pragma once
// The reference for periodic detections: every pair of boxes tested under the 3^D images
// around the nearest one (the shifts -1, 0, +1 around the rounded difference of the centres,
// in periods, on every periodic axis; only 0 on the others), with the relation the library
// documents (overlaps_with_shift). Since every extent is below half a period, a pair can only
// meet under one of them. Plus the scenes the periodic tests share.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "reference/random_boxes.hpp"
#include "smb/periodic.hpp"

namespace smb::test {

/// Every pair (a < b by name; names empty: the index) and shift under which box a overlaps
/// box b translated, sorted.
template <std::floating_point Real, int Dim>
std::vector<PeriodicPair> brute_force_periodic_pairs(std::span<const Box<Real, Dim>> boxes,
                                                     std::span<const BoxId> names,
                                                     const PeriodicDomain<Real, Dim>& domain) {
    std::vector<PeriodicPair> pairs;
    auto name = [&](std::size_t i) { return names.empty() ? static_cast<BoxId>(i) : names[i]; };
    // Where rounding lets two neighbouring shifts pass, the one nearer 0 on every axis is the
    // pair's (smb/periodic.hpp).
    auto nearer_overlaps = [&](const Box<Real, Dim>& a, const Box<Real, Dim>& b, std::array<std::int32_t, 3> shift) {
        for (int k = 0; k < Dim; ++k) {
            if (shift[k] == 0) continue;
            std::array<std::int32_t, 3> nearer = shift;
            nearer[k] -= shift[k] > 0 ? 1 : -1;
            if (overlaps_with_shift(a, b, nearer, domain)) return true;
        }
        return false;
    };
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
            std::size_t x = i;
            std::size_t y = j;
            if (name(y) < name(x)) std::swap(x, y);
            const Box<Real, Dim>& a = boxes[x];
            const Box<Real, Dim>& b = boxes[y];
            std::array<std::int32_t, 3> centre{};
            for (int k = 0; k < Dim; ++k) {
                if (!domain.periodic[k]) continue;
                const double ca = 0.5 * (static_cast<double>(a.min[k]) + static_cast<double>(a.max[k]));
                const double cb = 0.5 * (static_cast<double>(b.min[k]) + static_cast<double>(b.max[k]));
                centre[k] = static_cast<std::int32_t>(std::lround((ca - cb) / domain.period(k)));
            }
            const int images = Dim == 2 ? 9 : 27;
            for (int image = 0; image < images; ++image) {
                std::array<std::int32_t, 3> shift{};
                bool skip = false;
                int code = image;
                for (int k = 0; k < Dim; ++k) {
                    const int d = code % 3 - 1;
                    code /= 3;
                    if (!domain.periodic[k] && d != 0) skip = true;
                    shift[k] = domain.periodic[k] ? centre[k] + d : 0;
                }
                if (!skip && overlaps_with_shift(a, b, shift, domain) && !nearer_overlaps(a, b, shift))
                    pairs.push_back(PeriodicPair{name(x), name(y), shift});
            }
        }
    }
    sort_periodic_pairs(pairs);
    return pairs;
}

inline std::string describe(const PeriodicPair& p) {
    std::ostringstream out;
    out << "(" << p.a << ", " << p.b << ", [" << p.shift[0] << " " << p.shift[1] << " " << p.shift[2] << "])";
    return out.str();
}

/// Compares sorted copies; on a difference lists what is missing and what is extra.
inline ::testing::AssertionResult same_periodic_pairs(std::vector<PeriodicPair> reported,
                                                      std::vector<PeriodicPair> expected) {
    sort_periodic_pairs(reported);
    sort_periodic_pairs(expected);
    if (reported == expected) return ::testing::AssertionSuccess();
    std::vector<PeriodicPair> missing;
    std::vector<PeriodicPair> extra;
    auto less = [](const PeriodicPair& x, const PeriodicPair& y) {
        return std::tie(x.a, x.b, x.shift) < std::tie(y.a, y.b, y.shift);
    };
    std::set_difference(expected.begin(), expected.end(), reported.begin(), reported.end(), std::back_inserter(missing),
                        less);
    std::set_difference(reported.begin(), reported.end(), expected.begin(), expected.end(), std::back_inserter(extra),
                        less);
    std::ostringstream out;
    out << reported.size() << " pairs reported, " << expected.size() << " expected; missing:";
    for (std::size_t i = 0; i < std::min<std::size_t>(missing.size(), 10); ++i) out << " " << describe(missing[i]);
    out << "; extra (or repeated):";
    for (std::size_t i = 0; i < std::min<std::size_t>(extra.size(), 10); ++i) out << " " << describe(extra[i]);
    if (missing.empty() && extra.empty()) out << " (a pair is repeated)";
    return ::testing::AssertionFailure() << out.str();
}

/// The domain [0, side) on the axes whose bit is set in `axes`.
template <std::floating_point Real, int Dim>
PeriodicDomain<Real, Dim> cube_domain(double side, unsigned axes) {
    PeriodicDomain<Real, Dim> domain;
    for (int k = 0; k < Dim; ++k) {
        if ((axes >> k) & 1u) domain.wrap(k, Real(0), static_cast<Real>(side));
    }
    return domain;
}

/// A box of the domain: its centre uniform in [0, side) and wrapped there (as a DEM code wraps a
/// particle), so that it sticks out on either side; sides in [min_side, max_side].
template <std::floating_point Real, int Dim>
Box<Real, Dim> particle_box(Random& random, double side, double min_side, double max_side) {
    return random_box<Real, Dim>(random, 0, side, min_side, max_side);
}

/// The box translated by `periods` periods of `side` on every periodic axis of `domain`.
template <std::floating_point Real, int Dim>
Box<Real, Dim> translated(const Box<Real, Dim>& box, const PeriodicDomain<Real, Dim>& domain, int periods) {
    Box<Real, Dim> out = box;
    for (int k = 0; k < Dim; ++k) {
        if (!domain.periodic[k]) continue;
        const double t = periods * domain.period(k);
        out.min[k] = static_cast<Real>(box.min[k] + t);
        out.max[k] = static_cast<Real>(box.max[k] + t);
        if (out.max[k] < out.min[k]) out.max[k] = out.min[k];
    }
    return out;
}

/// Moves the box by up to `step` on every axis; where its centre leaves [0, side) on a
/// periodic axis, it is wrapped back by a period unless `keep_away` (then it drifts on, out of
/// the domain). Its extent stays as it was.
template <std::floating_point Real, int Dim>
Box<Real, Dim> moved(Random& random, const Box<Real, Dim>& box, const PeriodicDomain<Real, Dim>& domain, double step,
                     bool keep_away) {
    std::array<double, Dim> centre{};
    std::array<double, Dim> half{};
    for (int k = 0; k < Dim; ++k) {
        centre[k] = 0.5 * (double(box.min[k]) + double(box.max[k])) + uniform(random, -step, step);
        half[k] = 0.5 * (double(box.max[k]) - double(box.min[k]));
        if (domain.periodic[k] && !keep_away) {
            const double p = domain.period(k);
            if (centre[k] < double(domain.lo[k])) centre[k] += p;
            if (centre[k] >= double(domain.hi[k])) centre[k] -= p;
        }
    }
    return box_around<Real, Dim>(centre, half);
}

}  // namespace smb::test
