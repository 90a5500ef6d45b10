// SPDX-License-Identifier: MIT
#include "scenes/islands.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

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

    std::mt19937_64 layout_rng(spec.seed ^ 0x15a1du);
    std::uniform_real_distribution<double> anywhere(radius, std::max(radius, cube_side - radius));
    std::vector<std::array<double, Dim>> centres(island_count);
    for (auto& centre : centres)
        for (int k = 0; k < Dim; ++k) centre[k] = anywhere(layout_rng);

    auto place = [centres, radius](std::mt19937_64& rng) {
        std::uniform_int_distribution<std::size_t> which(0, centres.size() - 1);
        std::uniform_real_distribution<double> offset(-radius, radius);
        std::uniform_real_distribution<double> side(smallest_side, largest_side);
        PlacedBox<Dim> box;
        const auto& centre = centres[which(rng)];
        // Uniform in the ball: points of the enclosing cube, the ones outside drawn again.
        for (;;) {
            double distance = 0;
            for (int k = 0; k < Dim; ++k) {
                const double along = offset(rng);
                box.centre[k] = centre[k] + along;
                distance += along * along;
            }
            if (distance <= radius * radius) break;
        }
        for (int k = 0; k < Dim; ++k) box.sides[k] = side(rng);
        box.side_min = smallest_side;
        box.side_max = largest_side;
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, cube_side, largest_side, spec.update_factor, spec.seed,
                                              place);
}

template std::unique_ptr<Scene<2>> make_islands_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_islands_scene<3>(const SceneSpec&);

}  // namespace smb::bench
