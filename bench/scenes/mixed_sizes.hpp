// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// A mix of sizes, uniform in the cube: most sides in [0.1, 1] (H = 10), 1% of the boxes with
/// sides in [2, 8], and the first 8 boxes a quarter of the cube wide, like floors and walls
/// under a pile of grains. The small boxes alone pack the cube at density 0.2.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_mixed_sizes_scene(const SceneSpec& spec);

}  // namespace smb::bench
