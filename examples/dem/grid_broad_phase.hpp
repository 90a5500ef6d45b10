// SPDX-License-Identifier: MIT
#pragma once
// A uniform grid broad phase with a Verlet skin, as DEM and molecular dynamics codes write it:
// the baseline beside which the example measures smb (--broad-phase grid).
//
// Each box gets a fat box, grown by the skin on every side (as smb's Detector grows it, so
// that both hold the same candidates). A rebuild sorts the boxes
// into cubic cells as wide as the widest fat box (a counting sort), so that two fat boxes that
// overlap have their centres in the same or adjacent cells; each cell is tested against itself
// and 13 of its 26 neighbours (the half stencil), which finds every pair once. The pairs of fat
// boxes that overlap are the candidates, sorted by (a, b) once per rebuild. A step checks that
// every box is still inside its fat box (else it rebuilds everything, as LAMMPS does with
// "neigh_modify check yes") and tests the candidates: the pairs come out sorted by (a, b).

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace dem {

class GridBroadPhase {
public:
    /// `skin`: how far fat boxes stick out beyond the boxes on every side
    /// (smb::DetectorSettings::skin).
    explicit GridBroadPhase(double skin) : skin_(skin) {}

    /// Replaces `pairs` by every pair of `boxes` that overlap (closed convention, as smb),
    /// sorted by (a, b).
    void detect(std::span<const smb::Box3d> boxes, std::vector<smb::Pair>& pairs);

    [[nodiscard]] std::size_t rebuilds() const noexcept { return rebuilds_; }
    [[nodiscard]] std::size_t candidates() const noexcept { return candidates_.size(); }

private:
    void rebuild(std::span<const smb::Box3d> boxes);
    void sort_into_cells(std::span<const smb::Box3d> boxes);
    void pair_cells(std::size_t cell, std::size_t other);

    double skin_;
    std::size_t rebuilds_ = 0;
    std::vector<smb::Box3d> fat_;            // per box, as of the last rebuild
    std::vector<smb::Pair> candidates_;      // pairs of overlapping fat boxes, sorted by (a, b)
    std::array<std::size_t, 3> dims_{};      // cells per axis
    std::array<double, 3> lo_{};             // the grid's corner
    double inverse_cell_ = 0;                // 1 / cell side
    std::vector<std::uint32_t> cell_of_;     // per box
    std::vector<std::uint32_t> cell_start_;  // per cell, and one past the end: its boxes in order_
    std::vector<std::uint32_t> order_;       // box indices, cell by cell
    std::vector<smb::Box3d> sorted_fat_;     // fat boxes in order_, read in sequence by the scan
};

}  // namespace dem
