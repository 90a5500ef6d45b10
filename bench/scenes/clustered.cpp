// SPDX-License-Identifier: MIT
#include "scenes/clustered.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "scenes/around_centres.hpp"
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

    const auto centres = random_centres<Dim>(cluster_count, 0.0, cube_side, spec.seed ^ 0x5eedc1u);
    auto gaussian = [spread](std::mt19937_64& rng, const std::array<double, Dim>& centre) {
        std::normal_distribution<double> offset(0.0, spread);
        std::array<double, Dim> at{};
        for (int k = 0; k < Dim; ++k) at[k] = centre[k] + offset(rng);
        return at;
    };
    auto place = placed_around<Dim>(centres, smallest_side, largest_side, gaussian);
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, largest_side, spec.update_factor, spec.seed,
                                              place);
}

template std::unique_ptr<Scene<2>> make_clustered_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_clustered_scene<3>(const SceneSpec&);

}  // namespace smb::bench
