// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// Polydisperse particles: each box has a size s log-uniform over `decades` decades up to 1
/// (0.01–1 for two, 0.001–1 for three), its sides s times a factor uniform in [0.8, 1], spread
/// uniformly over a cube at packing density 0.2. Most boxes are small, a few are large, and the
/// large ones set a grid's cells.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_log_uniform_sizes_scene(const SceneSpec& spec, int decades);

}  // namespace smb::bench
