// SPDX-License-Identifier: MIT
#pragma once
// The cube and the side bounds of the paper's environment from its parameters, checked: one
// definition for DynamicEnvironment and EnvironmentShare, so that both refuse the same input
// with the same message and build the same cube.

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

}  // namespace smb::workload
