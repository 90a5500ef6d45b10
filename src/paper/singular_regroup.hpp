// SPDX-License-Identifier: MIT
#pragma once
// The regrouping of the paper's Section 2.4 (3) and steps 4-7 of its Section 3: a list of level
// l stays grouped by the segment its parent item fell in on level l - 1. From one step to the
// next only a few items change segment ("singular" items); the others ("normal") keep their
// place and their order, so each section stays almost sorted for DIS.
//
// The paper swaps singular items through holes in place, which works when every section keeps
// its length. Our cuts move to value changes and N changes between steps, so section lengths
// vary. The regrouping is in place all the same, in two linear passes: the first packs the normal
// items to the front, section by section, and sets the singular items aside; since a section's
// normal items can only have been preceded by fewer items than will precede it, each packed
// section lies at or before its new place, and the second pass, from the last section back,
// merges each section's normal items with the singular items that arrive in it (sorted among
// themselves), so that they land near their final place instead of at a hole. Only the singular
// items are ever copied out of the list.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"

namespace smb::detail {

/// A singular item set aside, with the section it moves to: the paper's stack array, one stack
/// per destination section once sorted.
template <std::floating_point Real>
struct SingularItem {
    SegmentId section;
    AxisEntry<Real> entry;
};

/// Scratch arrays of the regrouping, kept between steps so that steady-state steps allocate
/// nothing.
template <std::floating_point Real>
struct RegroupScratch {
    std::vector<SingularItem<Real>> singular;  // grouped by destination section once sorted
    std::vector<std::uint32_t> packed_end;     // end of each old section's packed normal items

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return singular.capacity() * sizeof(SingularItem<Real>) + packed_end.capacity() * sizeof(std::uint32_t);
    }
};

/// Regroups `list` (grouped by `old_section_begin`) plus `arrivals` (items new to the list), in
/// place, by the section of each item's parent, `parent_segment[item >> 1]`.
/// `new_section_begin` (size sections + 1) gives the regrouped offsets; `list` ends that long.
template <std::floating_point Real>
void regroup_by_parent_segment(std::vector<AxisEntry<Real>>& list, std::span<const std::uint32_t> old_section_begin,
                               std::span<const AxisEntry<Real>> arrivals, std::span<const SegmentId> parent_segment,
                               std::span<const std::uint32_t> new_section_begin, RegroupScratch<Real>& scratch) {
    const std::size_t new_sections = new_section_begin.size() - 1;
    const std::size_t old_sections = old_section_begin.empty() ? 0 : old_section_begin.size() - 1;
    auto& singular = scratch.singular;
    auto& packed_end = scratch.packed_end;
    singular.clear();
    packed_end.assign(new_sections, 0);

    // Pack the normal items to the front; set aside every item whose section changed.
    std::size_t write = 0;
    for (std::size_t j = 0; j < old_sections; ++j) {
        for (std::uint32_t i = old_section_begin[j]; i < old_section_begin[j + 1]; ++i) {
            const AxisEntry<Real> entry = list[i];
            const SegmentId section = parent_segment[entry.item >> 1];
            if (section == j) {
                list[write++] = entry;
            } else {
                singular.push_back({section, entry});
            }
        }
        if (j < new_sections) packed_end[j] = static_cast<std::uint32_t>(write);
    }
    for (std::size_t j = std::min(old_sections, new_sections); j < new_sections; ++j) {
        packed_end[j] = static_cast<std::uint32_t>(write);
    }
    for (const auto& entry : arrivals) singular.push_back({parent_segment[entry.item >> 1], entry});
    std::sort(singular.begin(), singular.end(), [](const SingularItem<Real>& a, const SingularItem<Real>& b) {
        if (a.section != b.section) return a.section < b.section;
        return entry_less(a.entry, b.entry);
    });

    // Merge from the back: every write lands at or after the packed items not yet read.
    list.resize(new_section_begin[new_sections]);
    auto arrived = singular.end();
    for (std::size_t j = new_sections; j-- > 0;) {
        const std::size_t normal_first = j == 0 ? 0 : packed_end[j - 1];
        std::size_t normal_end = packed_end[j];
        std::size_t out = new_section_begin[j + 1];
        while (arrived != singular.begin() && (arrived - 1)->section == j) {
            const AxisEntry<Real>& last_arrival = (arrived - 1)->entry;
            if (normal_end > normal_first && entry_less(last_arrival, list[normal_end - 1])) {
                list[--out] = list[--normal_end];
            } else {
                list[--out] = last_arrival;
                --arrived;
            }
        }
        SMB_ASSERT(out - normal_end == new_section_begin[j] - normal_first, "a section's count changed");
        if (out != normal_end)
            std::move_backward(list.begin() + normal_first, list.begin() + normal_end, list.begin() + out);
    }
    SMB_ASSERT(arrived == singular.begin(), "a singular item found no section");
}

}  // namespace smb::detail
