// SPDX-License-Identifier: MIT
#pragma once
// Seeded random boxes for the tests. Every generator takes the engine explicitly so that a
// failing test can print its seed and be replayed exactly.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "smb/box.hpp"

namespace smb::test {

using Random = std::mt19937_64;

inline double uniform(Random& random, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

inline std::size_t uniform_index(Random& random, std::size_t count) {
    return std::uniform_int_distribution<std::size_t>(0, count - 1)(random);
}

inline bool chance(Random& random, double probability) { return std::bernoulli_distribution(probability)(random); }

/// A size drawn so that its logarithm is uniform: sizes spread evenly over magnitudes.
inline double log_uniform(Random& random, double lo, double hi) {
    return std::exp(uniform(random, std::log(lo), std::log(hi)));
}

/// The box with the given centre and half extents, rounded to Real. Rounding is monotone,
/// so min <= max survives it.
template <std::floating_point Real, int Dim>
Box<Real, Dim> box_around(const std::array<double, Dim>& centre, const std::array<double, Dim>& half_extent) {
    Box<Real, Dim> box;
    for (int k = 0; k < Dim; ++k) {
        box.min[k] = static_cast<Real>(centre[k] - half_extent[k]);
        box.max[k] = static_cast<Real>(centre[k] + half_extent[k]);
    }
    return box;
}

/// A box with its centre uniform in [lo, hi)^Dim and each side uniform in [min_side, max_side].
template <std::floating_point Real, int Dim>
Box<Real, Dim> random_box(Random& random, double lo, double hi, double min_side, double max_side) {
    std::array<double, Dim> centre{};
    std::array<double, Dim> half{};
    for (int k = 0; k < Dim; ++k) {
        centre[k] = uniform(random, lo, hi);
        half[k] = 0.5 * uniform(random, min_side, max_side);
    }
    return box_around<Real, Dim>(centre, half);
}

/// The box moved by up to `max_shift` and with each side changed by up to `max_growth`
/// (never below zero), as in the paper's artificial dynamic environment (its Section 4).
template <std::floating_point Real, int Dim>
Box<Real, Dim> perturbed(Random& random, const Box<Real, Dim>& box, double max_shift, double max_growth) {
    std::array<double, Dim> centre{};
    std::array<double, Dim> half{};
    for (int k = 0; k < Dim; ++k) {
        const double lo = box.min[k];
        const double hi = box.max[k];
        centre[k] = 0.5 * (lo + hi) + uniform(random, -max_shift, max_shift);
        half[k] = std::max(0.0, 0.5 * (hi - lo) + 0.5 * uniform(random, -max_growth, max_growth));
    }
    return box_around<Real, Dim>(centre, half);
}

/// Four boxes at every point of a lattice of per_axis^3 points 3 apart: a unit box, one apart
/// from it by 1e-12 on x, one touching it on y, and one overlapping it by 1e-12 on z: pairs that
/// floats cannot tell apart from touching, in cells small enough to be tested pair by pair.
inline std::vector<Box3d> near_touching_lattice(int per_axis) {
    const double gap = 1e-12;
    std::vector<Box3d> boxes;
    for (int i = 0; i < per_axis; ++i) {
        for (int j = 0; j < per_axis; ++j) {
            for (int l = 0; l < per_axis; ++l) {
                const double x = 3.0 * i, y = 3.0 * j, z = 3.0 * l;
                boxes.push_back(Box3d{{x, y, z}, {x + 1, y + 1, z + 1}});
                boxes.push_back(Box3d{{x + 1 + gap, y, z}, {x + 2, y + 1, z + 1}});
                boxes.push_back(Box3d{{x, y + 1, z}, {x + 1, y + 2, z + 1}});
                boxes.push_back(Box3d{{x + 0.5, y + 0.5, z + 1 - gap}, {x + 1.5, y + 1.5, z + 2}});
            }
        }
    }
    return boxes;
}

}  // namespace smb::test
