// SPDX-License-Identifier: MIT
#pragma once
// The regrouping of the paper's Section 2.4 (3) and steps 4-7 of its Section 3: a list of level
// l stays grouped by the segment its parent item fell in on level l - 1. From one step to the
// next only a few items change segment ("singular" items); the others ("normal") keep their
// place and their order, so each section stays almost sorted for DIS.
//
// The paper swaps singular items through holes in place, which works when every section keeps
// its length. Our cuts move to value changes and N changes between steps, so section lengths
// vary; we therefore write the regrouped list into a second buffer: normal items in their old
// order, merged with the singular items that arrive in the section (sorted among themselves),
// so that arrivals land near their final place instead of at a hole. Still one linear pass
// plus a sort of the singular items only.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"

namespace smb::detail {

/// Scratch arrays of the regrouping, kept between steps so that steady-state steps allocate
/// nothing: the paper's stack array (one stack per destination section) and its pointers.
template <std::floating_point Real>
struct RegroupScratch {
    std::vector<AxisEntry<Real>> singular;    // singular items in arrival order
    std::vector<SegmentId> singular_section;  // their destination sections
    std::vector<AxisEntry<Real>> stacks;      // the stack array, grouped by section
    std::vector<std::uint32_t> stack_begin;   // stack pointers

    template <class Trim>
    void trim(Trim&& trim_buffer) {
        trim_buffer(singular);
        trim_buffer(singular_section);
        trim_buffer(stacks);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return singular.capacity() * sizeof(AxisEntry<Real>) + singular_section.capacity() * sizeof(SegmentId) +
               stacks.capacity() * sizeof(AxisEntry<Real>) + stack_begin.capacity() * sizeof(std::uint32_t);
    }
};

/// Regroups `list` (grouped by `old_section_begin`) plus `arrivals` (items new to the list) by
/// the section of each item's parent, `parent_segment[item >> 1]`. `new_section_begin` (size
/// sections + 1) gives the regrouped offsets. The result goes to `out`.
template <std::floating_point Real>
void regroup_by_parent_segment(std::span<const AxisEntry<Real>> list, std::span<const std::uint32_t> old_section_begin,
                               std::span<const AxisEntry<Real>> arrivals, std::span<const SegmentId> parent_segment,
                               std::span<const std::uint32_t> new_section_begin, std::vector<AxisEntry<Real>>& out,
                               RegroupScratch<Real>& scratch) {
    const std::size_t new_sections = new_section_begin.size() - 1;
    const std::size_t old_sections = old_section_begin.empty() ? 0 : old_section_begin.size() - 1;
    auto& singular = scratch.singular;
    auto& destination = scratch.singular_section;
    singular.clear();
    destination.clear();

    // Push: every item whose section changed, and every arrival, onto its destination's stack.
    for (std::size_t j = 0; j < old_sections; ++j) {
        for (std::uint32_t i = old_section_begin[j]; i < old_section_begin[j + 1]; ++i) {
            const SegmentId section = parent_segment[list[i].item >> 1];
            if (section != j) {
                singular.push_back(list[i]);
                destination.push_back(section);
            }
        }
    }
    for (const auto& entry : arrivals) {
        singular.push_back(entry);
        destination.push_back(parent_segment[entry.item >> 1]);
    }
    auto& stack_begin = scratch.stack_begin;
    stack_begin.assign(new_sections + 1, 0);
    for (const SegmentId section : destination) ++stack_begin[section + 1];
    for (std::size_t j = 0; j < new_sections; ++j) stack_begin[j + 1] += stack_begin[j];
    auto& stacks = scratch.stacks;
    stacks.resize(singular.size());
    {
        std::vector<std::uint32_t>& top = scratch.stack_begin;  // reused as cursors, restored below
        for (std::size_t s = 0; s < singular.size(); ++s) stacks[top[destination[s]]++] = singular[s];
        for (std::size_t j = new_sections; j > 0; --j) top[j] = top[j - 1];
        top[0] = 0;
    }

    // Pop: each section is its normal items, in their old order, merged with its arrivals.
    out.resize(new_section_begin[new_sections]);
    for (std::size_t j = 0; j < new_sections; ++j) {
        auto arrived_first = stacks.begin() + stack_begin[j];
        auto arrived_last = stacks.begin() + stack_begin[j + 1];
        std::sort(arrived_first, arrived_last, EntryLess{});
        std::size_t write = new_section_begin[j];
        if (j < old_sections) {
            for (std::uint32_t i = old_section_begin[j]; i < old_section_begin[j + 1]; ++i) {
                const auto& entry = list[i];
                if (parent_segment[entry.item >> 1] != j) continue;
                while (arrived_first != arrived_last && entry_less(*arrived_first, entry)) {
                    out[write++] = *arrived_first++;
                }
                out[write++] = entry;
            }
        }
        while (arrived_first != arrived_last) out[write++] = *arrived_first++;
    }
}

}  // namespace smb::detail
