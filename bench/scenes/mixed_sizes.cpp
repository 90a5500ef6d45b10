// SPDX-License-Identifier: MIT
#include "scenes/mixed_sizes.hpp"

#include <cmath>
#include <random>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr double small_density = 0.2;
constexpr double small_min = 0.1;
constexpr double small_max = 1.0;
constexpr double medium_min = 2.0;
constexpr double medium_max = 8.0;
constexpr double medium_share = 0.01;
constexpr std::size_t huge_count = 8;
constexpr double huge_fraction_of_cube = 0.25;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_mixed_sizes_scene(const SceneSpec& spec) {
    const double mean_small = 0.5 * (small_min + small_max);
    const double cube_side =
        std::pow(static_cast<double>(spec.boxes) * std::pow(mean_small, Dim) / small_density, 1.0 / Dim);
    const double huge_side = huge_fraction_of_cube * cube_side;

    // The first boxes placed are the huge ones; later insertions are small or medium.
    auto place = [cube_side, huge_side, placed = std::size_t{0}](std::mt19937_64& rng) mutable {
        std::uniform_real_distribution<double> anywhere(0.0, cube_side);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        PlacedBox<Dim> box;
        if (placed++ < huge_count) {
            box.side_min = huge_side - 1.0;
            box.side_max = huge_side + 1.0;
        } else if (unit(rng) < medium_share) {
            box.side_min = medium_min;
            box.side_max = medium_max;
        } else {
            box.side_min = small_min;
            box.side_max = small_max;
        }
        std::uniform_real_distribution<double> side(box.side_min, box.side_max);
        for (int k = 0; k < Dim; ++k) box.sides[k] = side(rng);
        for (int k = 0; k < Dim; ++k) box.centre[k] = anywhere(rng);
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, small_max, spec.update_factor, spec.seed, place);
}

template std::unique_ptr<Scene<2>> make_mixed_sizes_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_mixed_sizes_scene<3>(const SceneSpec&);

}  // namespace smb::bench
