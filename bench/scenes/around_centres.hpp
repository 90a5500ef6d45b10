// SPDX-License-Identifier: MIT
#pragma once
// The boxes of a scene gathered around a few random centres (islands, Gaussian clusters): where
// the centres lie, and a placement that picks one for each box and draws its sides.

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {

/// `count` centres drawn uniformly in [low, high) on every axis, from the scene's layout seed.
template <int Dim>
std::vector<std::array<double, Dim>> random_centres(int count, double low, double high, std::uint64_t layout_seed) {
    std::mt19937_64 layout_rng(layout_seed);
    std::uniform_real_distribution<double> anywhere(low, high);
    std::vector<std::array<double, Dim>> centres(static_cast<std::size_t>(count));
    for (auto& centre : centres)
        for (int k = 0; k < Dim; ++k) centre[k] = anywhere(layout_rng);
    return centres;
}

/// A placement for MovingBoxes: each box near one of `centres`, chosen uniformly, at the point
/// `near(rng, centre)` returns; its sides uniform in [smallest_side, largest_side).
template <int Dim, class Near>
auto placed_around(std::vector<std::array<double, Dim>> centres, double smallest_side, double largest_side, Near near) {
    return [centres = std::move(centres), smallest_side, largest_side, near](std::mt19937_64& rng) {
        std::uniform_int_distribution<std::size_t> which(0, centres.size() - 1);
        std::uniform_real_distribution<double> side(smallest_side, largest_side);
        PlacedBox<Dim> box;
        box.centre = near(rng, centres[which(rng)]);
        for (int k = 0; k < Dim; ++k) box.sides[k] = side(rng);
        box.side_min = smallest_side;
        box.side_max = largest_side;
        return box;
    };
}

}  // namespace smb::bench
