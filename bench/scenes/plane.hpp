// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// Boxes on a plane: boxes of sides uniform in [0.4, 1] whose centres keep to a slab two units
/// thick (a strip in 2D), packed at density 0.4 in it, as grains on a floor. Along the last axis
/// the boxes move by λ times the slab's thickness, so the slab stays thin.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_plane_scene(const SceneSpec& spec);

}  // namespace smb::bench
