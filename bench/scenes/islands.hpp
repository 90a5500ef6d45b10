// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// Dense clusters in empty space: 16 balls (discs in 2D), each packed uniformly at density 0.4
/// with boxes of sides uniform in [0.4, 1], in a cube whose overall packing density is 0.002.
/// Nearly all of the space is empty, so a dense grid either holds mostly empty cells or, capped
/// in cells, crowds each cluster into a few.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_islands_scene(const SceneSpec& spec);

}  // namespace smb::bench
