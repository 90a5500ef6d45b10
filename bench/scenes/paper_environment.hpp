// SPDX-License-Identifier: MIT
#pragma once

#include <memory>

#include "scenes/scene.hpp"

namespace smb::bench {

/// The paper's artificial dynamic environment (Section 4.1) from smb::workload, at packing
/// density E = 0.4 and size ratio H = 2.5 (inside the paper's ranges 0.31-0.43 and 1.4-3.3).
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_paper_scene(const SceneSpec& spec);

/// The sparse setting of the paper's Table 2: H = 10 in a cube of side x = 200 (3D only; the
/// paper runs it at Λ = 1e-5 and N = 400k-800k, where E is 0.008-0.017).
[[nodiscard]] std::unique_ptr<Scene<3>> make_sparse_scene(const SceneSpec& spec);

}  // namespace smb::bench
