// SPDX-License-Identifier: MIT
#include "scenes/islands.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "scenes/around_centres.hpp"
#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr int island_count = 16;
constexpr double island_density = 0.4;
constexpr double overall_density = 0.002;
constexpr double smallest_side = 0.4;
constexpr double largest_side = 1.0;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_islands_scene(const SceneSpec& spec) {
    const double n = static_cast<double>(spec.boxes);
    // Independent sides: the mean volume is the mean side to the power Dim.
    const double volume_moment = std::pow(0.5 * (smallest_side + largest_side), Dim);
    const double cube_side = std::pow(n * volume_moment / overall_density, 1.0 / Dim);
    // The volume of a unit ball: π in 2D, 4π/3 in 3D.
    const double unit_ball = Dim == 2 ? std::numbers::pi : 4 * std::numbers::pi / 3;
    const double island_volume = n / island_count * volume_moment / island_density;
    const double radius = std::pow(island_volume / unit_ball, 1.0 / Dim);

    const auto centres =
        random_centres<Dim>(island_count, radius, std::max(radius, cube_side - radius), spec.seed ^ 0x15a1du);
    // Uniform in the ball: points of the enclosing cube, the ones outside drawn again.
    auto in_ball = [radius](std::mt19937_64& rng, const std::array<double, Dim>& centre) {
        std::uniform_real_distribution<double> offset(-radius, radius);
        std::array<double, Dim> at{};
        for (;;) {
            double distance = 0;
            for (int k = 0; k < Dim; ++k) {
                const double along = offset(rng);
                at[k] = centre[k] + along;
                distance += along * along;
            }
            if (distance <= radius * radius) return at;
        }
    };
    auto place = placed_around<Dim>(centres, smallest_side, largest_side, in_ball);
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, largest_side, spec.update_factor, spec.seed,
                                              place);
}

template std::unique_ptr<Scene<2>> make_islands_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_islands_scene<3>(const SceneSpec&);

}  // namespace smb::bench
