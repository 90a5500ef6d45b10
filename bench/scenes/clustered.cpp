// SPDX-License-Identifier: MIT
#include "scenes/clustered.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr int cluster_count = 32;
constexpr double global_density = 0.02;
constexpr double core_density = 0.5;
constexpr double smallest_side = 0.5;
constexpr double largest_side = 1.0;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_clustered_scene(const SceneSpec& spec) {
    const double n = static_cast<double>(spec.boxes);
    const double mean_side = 0.5 * (smallest_side + largest_side);
    const double mean_volume = std::pow(mean_side, Dim);
    const double cube_side = std::pow(n * mean_volume / global_density, 1.0 / Dim);
    // A Gaussian cluster of m boxes has peak number density m / ((2π)^(Dim/2) σ^Dim); σ is
    // chosen so that its peak packing density is core_density.
    const double per_cluster = n / cluster_count;
    const double spread =
        std::pow(per_cluster * mean_volume / (core_density * std::pow(2 * std::numbers::pi, 0.5 * Dim)), 1.0 / Dim);

    std::mt19937_64 layout_rng(spec.seed ^ 0x5eedc1u);
    std::uniform_real_distribution<double> anywhere(0.0, cube_side);
    std::vector<std::array<double, Dim>> centres(cluster_count);
    for (auto& centre : centres)
        for (int k = 0; k < Dim; ++k) centre[k] = anywhere(layout_rng);

    auto place = [centres, spread](std::mt19937_64& rng) {
        std::uniform_int_distribution<std::size_t> which(0, centres.size() - 1);
        std::normal_distribution<double> offset(0.0, spread);
        std::uniform_real_distribution<double> side(smallest_side, largest_side);
        PlacedBox<Dim> box;
        const auto& centre = centres[which(rng)];
        for (int k = 0; k < Dim; ++k) box.centre[k] = centre[k] + offset(rng);
        for (int k = 0; k < Dim; ++k) box.sides[k] = side(rng);
        box.side_min = smallest_side;
        box.side_max = largest_side;
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, largest_side, spec.update_factor, spec.seed,
                                              place);
}

template std::unique_ptr<Scene<2>> make_clustered_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_clustered_scene<3>(const SceneSpec&);

}  // namespace smb::bench
