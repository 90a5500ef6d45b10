// SPDX-License-Identifier: MIT
#pragma once
// The paper's segment rule (its remark 4 of Section 2.4; SegmentRule::twice_largest_box in
// settings.hpp): every segment of a level at least twice the largest extent of any box on the
// level's axis, so that no box spans three segments (the paper's Fig. 5). Boxes change size every
// step, so the largest is measured afresh at every detection, in one pass over the boxes.

#include <algorithm>
#include <array>
#include <span>

#include "smb/box.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

/// The shortest segment allowed on each level l (whose axis is Dim - 1 - l) under `rule`: zero
/// everywhere for SegmentRule::from_count. Where every box is flat on an axis the length is zero
/// and the counts alone cut it: a box whose two ends share one key never spans two segments.
template <std::floating_point Real, int Dim>
std::array<Real, Dim> shortest_segments(SegmentRule rule, std::span<const Box<Real, Dim>> boxes) {
    std::array<Real, Dim> shortest{};
    if (rule != SegmentRule::twice_largest_box) return shortest;
    std::array<Real, Dim> largest{};
    for (const auto& box : boxes) {
        for (int axis = 0; axis < Dim; ++axis) largest[axis] = std::max(largest[axis], box.max[axis] - box.min[axis]);
    }
    for (int level = 0; level < Dim; ++level) shortest[level] = 2 * largest[Dim - 1 - level];
    return shortest;
}

}  // namespace smb::detail
