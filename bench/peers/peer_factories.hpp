// SPDX-License-Identifier: MIT
#pragma once
// One factory per method; each is defined in the file named after it. The optional peers
// (Bullet, Box2D, CGAL) are compiled only when their packages were found.

#include <memory>

#include "peers/peer.hpp"
#include "smb/settings.hpp"

namespace smb::bench {

/// smb itself, driven incrementally through smb::World: remove, update, insert, detect.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_smb_world_peer(const WorldSettings& settings);

/// The same over double coordinates (the scene's float boxes widened, untimed, beforehand).
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_smb_world_double_peer(const WorldSettings& settings);

/// smb::Detector over an array in which each body keeps its index (no ids inside smb).
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_smb_detector_peer(const DetectorSettings& settings,
                                                                std::size_t renumber_every = 0);

/// Every pair tested, O(N^2): the reference on small scenes.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_brute_force_peer();

/// "Box pruning": a full re-sort on x every step, then a sweep that tests the other axes.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_box_pruning_peer();

/// A uniform grid rebuilt from scratch every step: each box once, in the cell of its lower
/// corner, rows of thin cells tested 4 to 16 boxes a compare (peers/uniform_grid.hpp); 1 or 2
/// threads.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_uniform_grid_peer(int threads);
/// The grid on one thread over an array renumbered in its cell order every `renumber_every` steps.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_sorted_uniform_grid_peer(std::size_t renumber_every);

/// The same grid over boxes fattened by `skin`, listing the pairs of fat boxes that overlap;
/// a step tests only those, until a box leaves its fat box (a Verlet list).
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_verlet_grid_peer(float skin);

/// A uniform grid rebuilt from scratch every step with each box in every cell it overlaps,
/// cells twice the mean box size: the textbook scheme.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_uniform_grid_every_cell_peer();

/// CGAL's box_intersection_d on closed boxes, stateless, every step from scratch.
template <int Dim>
[[nodiscard]] std::unique_ptr<Peer<Dim>> make_cgal_box_intersection_peer();

/// Bullet's bt32BitAxisSweep3 (incremental sweep and prune), 3D.
[[nodiscard]] std::unique_ptr<Peer<3>> make_bullet_axis_sweep_peer();

/// Bullet's btDbvtBroadphase (two dynamic AABB trees), 3D.
[[nodiscard]] std::unique_ptr<Peer<3>> make_bullet_dbvt_peer();

/// Box2D 2.4's b2DynamicTree with a persistent pair list, as b2World drives it, 2D.
[[nodiscard]] std::unique_ptr<Peer<2>> make_box2d_dynamic_tree_peer();

}  // namespace smb::bench
