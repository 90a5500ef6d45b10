// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// Boxes gathered in 32 Gaussian clusters inside a mostly empty cube: the overall packing
/// density is 0.02, but each cluster's core is packed at about 0.5, the paper's upper bound
/// for good temporal coherence. Box sides are uniform in [0.5, 1] (H = 2). A spatial grid
/// sized for the average density sees either huge cells in the clusters or mostly empty ones.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_clustered_scene(const SceneSpec& spec);

}  // namespace smb::bench
