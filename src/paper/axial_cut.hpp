// SPDX-License-Identifier: MIT
#pragma once
// The axial cut of the paper's Section 2.3: a sorted section is cut into segments holding
// (nearly) equal numbers of items, so that cells follow the boxes, not the space.
//
// Deviation from the paper (docs/algorithm.md): a cut is never placed between two items with
// the same coordinate; it moves forward to the next change of value. Without this rule a flat
// layer of boxes (all z equal) would be cut through its middle: each box's min and max would
// land in different segments far apart and every box would look oversized. With it, segment
// boundaries are true coordinate planes, which the proof of exactness relies on.
//
// With the paper's segment rule (its remark 4 of Section 2.4; SegmentRule::twice_largest_box) a
// cut also moves forward until the segment is twice the largest box long on the axis, so that no
// box spans three segments (the paper's Fig. 5). Boxes change size every step, so the largest is
// measured afresh at every detection.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "paper/axis_entry.hpp"
#include "smb/box.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

using SegmentId = std::uint32_t;

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

/// Cuts `section` (sorted) into `segments` segments, none of them empty unless the section has
/// run out of items. Writes `first_segment` + its segment number for every item into
/// `segment_of` (the paper's index array, by item id), and appends the list offset (relative to
/// `section_offset`) at which each segment begins to `segment_begin`. A positive `min_length` is
/// the segment rule: every segment but the last reaches at least that far on the axis, from its
/// first key to the next segment's first key.
template <std::floating_point Real>
void cut_section(std::span<const AxisEntry<Real>> section, std::size_t section_offset, SegmentId segments,
                 SegmentId first_segment, std::span<SegmentId> segment_of, std::vector<std::uint32_t>& segment_begin,
                 Real min_length = 0) {
    const std::size_t n = section.size();
    std::size_t begin = 0;
    for (SegmentId s = 0; s < segments; ++s) {
        std::size_t end = n;
        if (s + 1 < segments && begin < n) {
            // Share what is left evenly among the segments left, so that a long run of equal
            // values that pushed a cut forward leaves no empty segment before the list's end:
            // empty segments come last, and a box's two ends are never two segments apart
            // merely because an empty segment lies between them.
            end = begin + std::max<std::size_t>(1, (n - begin) / (segments - s));
            if (min_length > 0 && end < n) {
                // The first key at least min_length past this segment's first: a change of
                // value, so the loop below leaves it where it is.
                const Real reach = section[begin].key + min_length;
                if (section[end].key < reach) {
                    end = static_cast<std::size_t>(
                        std::partition_point(section.begin() + static_cast<std::ptrdiff_t>(end), section.end(),
                                             [reach](const AxisEntry<Real>& entry) { return entry.key < reach; }) -
                        section.begin());
                }
            }
            while (end < n && !(section[end - 1].key < section[end].key)) ++end;
        }
        segment_begin.push_back(static_cast<std::uint32_t>(section_offset + begin));
        for (std::size_t i = begin; i < end; ++i) segment_of[section[i].item] = first_segment + s;
        begin = end;
    }
}

}  // namespace smb::detail
