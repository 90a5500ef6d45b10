// SPDX-License-Identifier: MIT
#include "scenes/plane.hpp"

#include <cmath>
#include <random>

#include "scenes/moving_boxes.hpp"

namespace smb::bench {
namespace {

constexpr double packing_density = 0.4;
constexpr double thickness = 2.0;
constexpr double smallest_side = 0.4;
constexpr double largest_side = 1.0;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_plane_scene(const SceneSpec& spec) {
    const double volume_moment = std::pow(0.5 * (smallest_side + largest_side), Dim);
    const double extent =
        std::pow(static_cast<double>(spec.boxes) * volume_moment / (packing_density * thickness), 1.0 / (Dim - 1));
    auto domain = PlacedBox<Dim>::filled(extent);
    domain[Dim - 1] = thickness;

    auto place = [domain](std::mt19937_64& rng) {
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::uniform_real_distribution<double> side(smallest_side, largest_side);
        PlacedBox<Dim> box;
        for (int k = 0; k < Dim; ++k) box.centre[k] = unit(rng) * domain[k];
        for (int k = 0; k < Dim; ++k) box.sides[k] = side(rng);
        box.side_min = smallest_side;
        box.side_max = largest_side;
        return box;
    };
    return std::make_unique<MovingBoxes<Dim>>(spec.boxes, domain, largest_side, spec.update_factor, spec.seed, place);
}

template std::unique_ptr<Scene<2>> make_plane_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_plane_scene<3>(const SceneSpec&);

}  // namespace smb::bench
