// SPDX-License-Identifier: MIT
#include "scenes/log_uniform_sizes.hpp"

#include <cmath>
#include <random>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr double packing_density = 0.2;
constexpr double shape_low = 0.8;  // sides are the size times a factor in [shape_low, 1]

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_log_uniform_sizes_scene(const SceneSpec& spec, int decades) {
    const double smallest = std::pow(10.0, -decades);
    const double log_range = std::log(1 / smallest);
    // E[s^D] for s log-uniform in [smallest, 1], times E[f^D] for f uniform in [shape_low, 1].
    const double size_moment = (1 - std::pow(smallest, Dim)) / (Dim * log_range);
    const double shape_moment = (1 - std::pow(shape_low, Dim + 1)) / ((Dim + 1) * (1 - shape_low));
    const double cube_side =
        std::pow(static_cast<double>(spec.boxes) * size_moment * shape_moment / packing_density, 1.0 / Dim);

    auto place = [cube_side, log_range](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> anywhere(0.0, cube_side);
        std::uniform_real_distribution<double> exponent(-log_range, 0.0);
        std::uniform_real_distribution<double> shape(shape_low, 1.0);
        PlacedBox<Dim> box;
        const double size = std::exp(exponent(rng));
        box.side_min = shape_low * size;
        box.side_max = size;
        for (int k = 0; k < Dim; ++k) box.sides[k] = size * shape(rng);
        for (int k = 0; k < Dim; ++k) box.centre[k] = anywhere(rng);
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, 1.0, spec.update_factor, spec.seed, place);
}

template std::unique_ptr<Scene<2>> make_log_uniform_sizes_scene<2>(const SceneSpec&, int);
template std::unique_ptr<Scene<3>> make_log_uniform_sizes_scene<3>(const SceneSpec&, int);

}  // namespace smb::bench
