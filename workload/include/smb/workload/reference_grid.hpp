// SPDX-License-Identifier: MIT
#pragma once
// An exact pair finder independent of the SMB pipeline, fast enough for the large scenes of
// `smb run` (a uniform grid, about linear time for boxes of similar size).

#include <concepts>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::workload {

/// Every pair of overlapping boxes (closed convention), box i under ids[i], sorted in (a, b)
/// order with a < b. Exact for any input: boxes much larger than the rest are taken out of the
/// grid and checked against the grid cells they cover and against each other, so one huge box
/// costs O(n), not O(n^2). Ids must be distinct. Throws std::invalid_argument on mismatched
/// spans or an invalid box, std::length_error above 2^32 - 1 boxes.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::vector<Pair> grid_pairs(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes);

}  // namespace smb::workload
