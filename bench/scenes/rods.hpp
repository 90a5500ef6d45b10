// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// Long rods: each box has one side, along an axis drawn at random, 10 to 50 times its others
/// (the aspect drawn uniformly per box); the long side is uniform in [0.5, 1], so the thin ones
/// lie in [0.01, 0.1]. Spread uniformly over a cube at packing density 0.05. The largest extent
/// on every axis is that of a long side, many times a typical box's.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_rods_scene(const SceneSpec& spec);

}  // namespace smb::bench
