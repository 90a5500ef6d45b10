// SPDX-License-Identifier: MIT
#include "scenes/rods.hpp"

#include <cmath>
#include <random>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr double packing_density = 0.05;
constexpr double least_aspect = 10;
constexpr double most_aspect = 50;
constexpr double shortest_long_side = 0.5;
constexpr double longest_long_side = 1.0;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_rods_scene(const SceneSpec& spec) {
    // The mean volume, long side l times (l / a)^(Dim - 1), estimated from a fixed sample.
    std::mt19937_64 sample_rng(0x60d5u);
    std::uniform_real_distribution<double> long_side(shortest_long_side, longest_long_side);
    std::uniform_real_distribution<double> sample_aspect(least_aspect, most_aspect);
    double volume_sum = 0;
    constexpr int sample_count = 4096;
    for (int i = 0; i < sample_count; ++i) {
        const double length = long_side(sample_rng);
        volume_sum += length * std::pow(length / sample_aspect(sample_rng), Dim - 1);
    }
    const double cube_side =
        std::pow(static_cast<double>(spec.boxes) * volume_sum / sample_count / packing_density, 1.0 / Dim);

    auto place = [cube_side](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> anywhere(0.0, cube_side);
        std::uniform_real_distribution<double> length_of(shortest_long_side, longest_long_side);
        std::uniform_real_distribution<double> aspect_of(least_aspect, most_aspect);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::uniform_int_distribution<int> axis_of(0, Dim - 1);
        PlacedBox<Dim> box;
        const double aspect = aspect_of(rng);
        const int axis = axis_of(rng);
        // Thin sides in [0.5, 1] / aspect, the long one that range stretched by the aspect.
        box.side_min = shortest_long_side / aspect;
        box.side_max = longest_long_side / aspect;
        box.stretch[axis] = aspect;
        const double length = length_of(rng);
        for (int k = 0; k < Dim; ++k) {
            const double thin = (box.side_min + unit(rng) * (box.side_max - box.side_min));
            box.sides[k] = k == axis ? length : thin;
        }
        for (int k = 0; k < Dim; ++k) box.centre[k] = anywhere(rng);
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, longest_long_side, spec.update_factor, spec.seed,
                                              place);
}

template std::unique_ptr<Scene<2>> make_rods_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_rods_scene<3>(const SceneSpec&);

}  // namespace smb::bench
