// SPDX-License-Identifier: MIT
#pragma once
// The scenes of the comparison: a stream of time steps, each the complete set of boxes under
// stable ids plus what changed since the previous step. Every method reads the same stream.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::bench {

/// Every method runs in single precision: Bullet and Box2D store floats, so float boxes are the
/// common ground, and all methods then decide overlap on bit-identical coordinates.
template <int Dim>
using BenchBox = Box<float, Dim>;

/// One time step. Survivors of the previous step come first (positions below first_inserted),
/// boxes inserted in this step after them. The spans stay valid until the next advance().
template <int Dim>
struct SceneStep {
    std::span<const BoxId> ids;
    std::span<const BenchBox<Dim>> boxes;
    std::span<const BoxId> removed_ids;
    std::size_t first_inserted = 0;
    std::size_t index = 0;  ///< 0 for the initial placement

    [[nodiscard]] std::size_t size() const noexcept { return ids.size(); }
    [[nodiscard]] std::size_t inserted_count() const noexcept { return ids.size() - first_inserted; }
};

template <int Dim>
class Scene {
public:
    virtual ~Scene() = default;
    /// The next step: the first call gives step 0 (every box inserted).
    virtual const SceneStep<Dim>& advance() = 0;
};

/// What to generate. `family` is one of: paper (the paper's Section 4.1 environment), sparse
/// (its Table 2 setting, 3D), clustered, mixed (a mix of sizes with a few very large boxes),
/// loguniform2 and loguniform3 (sizes log-uniform over two or three decades), islands (dense
/// clusters in empty space), plane (boxes on a plane), rods (one side 10–50 times the others).
struct SceneSpec {
    std::string family = "paper";
    int dimension = 3;
    std::size_t boxes = 10000;
    double update_factor = 1e-3;
    std::uint64_t seed = 1;
};

/// A short name for tables and file names, e.g. "paper3d-L1e-3".
[[nodiscard]] std::string scene_label(const SceneSpec& spec);

/// Throws std::invalid_argument for an unknown family or one that has no such dimension.
template <int Dim>
[[nodiscard]] std::unique_ptr<Scene<Dim>> make_scene(const SceneSpec& spec);

}  // namespace smb::bench
