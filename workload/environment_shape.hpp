// SPDX-License-Identifier: MIT
#pragma once
// The cube and the side bounds of the paper's environment from its parameters, checked: one
// definition for DynamicEnvironment and EnvironmentShare, so that both refuse the same input
// with the same message and build the same cube.

#include <algorithm>
#include <array>

#include "smb/box.hpp"
#include "smb/workload/dynamic_environment.hpp"

namespace smb::workload {

struct EnvironmentShape {
    double cube_side = 0;
    double min_side = 0;
    double max_side = 1;
    double packing_density = 0;
};

/// Throws std::invalid_argument on parameters out of range (see DynamicEnvironment).
[[nodiscard]] EnvironmentShape environment_shape(const EnvironmentParams& params, int dim);

/// The box of centre `centre` and sides `sides` in a cube of side `cube_side`. The clamps absorb
/// the last-bit rounding of centre +- half at the cube's walls.
template <int Dim>
[[nodiscard]] Box<double, Dim> box_in_cube(const std::array<double, Dim>& centre, const std::array<double, Dim>& sides,
                                           double cube_side) {
    Box<double, Dim> box;
    for (int k = 0; k < Dim; ++k) {
        const double half = sides[k] / 2;
        box.min[k] = std::max(0.0, centre[k] - half);
        box.max[k] = std::min(cube_side, centre[k] + half);
    }
    return box;
}

}  // namespace smb::workload
