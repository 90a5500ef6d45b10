// SPDX-License-Identifier: MIT
#pragma once
// One level of the paper's cut: its persistent list (Y1, X12 in 2D; Z1, Y12, X123 in 3D), sorted
// by DIS within each section, and the axial cut of every section into segments. The index array
// that gives every item its segment is a per-step array that all levels share (the pipeline's):
// a level's is read only by the next level's regrouping, before that level is cut. Also how the
// lists grow from one detection to the next: room for what arrives without doubling, and
// arrivals merged in place.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/id_index.hpp"
#include "core/slot_renumbering.hpp"
#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"
#include "paper/shell_sort.hpp"

namespace smb::detail {

/// Grows `list` to hold `length` items with a sixteenth to spare, and gives back what is more
/// than a quarter above it: vectors that double would hold up to twice the lists' bytes, and
/// more after N has shrunk.
template <class Vector>
void fit_capacity(Vector& list, std::size_t length) {
    if (length > list.capacity()) {
        list.reserve(length + length / 16);
    } else if (list.capacity() > length + length / 4 && list.capacity() > 4096) {
        Vector smaller;
        smaller.reserve(std::max(length, list.size()) + length / 16);
        smaller.assign(list.begin(), list.end());
        list.swap(smaller);
    }
}

/// Merges the sorted `arrivals` into the sorted `list` in place, from the back.
template <class Entry>
void merge_from_back(std::vector<Entry>& list, const std::vector<Entry>& arrivals) {
    std::size_t kept = list.size();
    std::size_t arrived = arrivals.size();
    list.resize(kept + arrived);
    std::size_t out = list.size();
    while (arrived > 0) {
        if (kept > 0 && entry_less(arrivals[arrived - 1], list[kept - 1])) {
            list[--out] = list[--kept];
        } else {
            list[--out] = arrivals[--arrived];
        }
    }
}

template <std::floating_point Real>
struct PaperLevel {
    using Entry = AxisEntry<Real>;

    std::vector<Entry> list;                   // grouped by section, sorted within each
    std::vector<std::uint32_t> section_begin;  // offsets of the sections in `list`
    std::vector<std::uint32_t> segment_begin;  // offsets of the segments (after the cut)
    DisController dis;

    /// Renumbers the items after BoxStore::compact() dropped removed slots, keeping the list's
    /// order; an item is its slot shifted by `shift` bits, the corner in the bits below.
    void renumber(const SlotRenumbering& renumbering, int shift) {
        const Item low_bits = (Item{1} << shift) - 1;
        std::size_t write = 0;
        for (std::size_t j = 0; j + 1 < section_begin.size(); ++j) {
            const std::uint32_t first = section_begin[j];
            const std::uint32_t last = section_begin[j + 1];
            section_begin[j] = static_cast<std::uint32_t>(write);
            for (std::uint32_t i = first; i < last; ++i) {
                const Entry entry = list[i];
                const Slot slot = renumbering(static_cast<Slot>(entry.item >> shift));
                if (slot == kNoSlot) continue;
                list[write++] = Entry{entry.key, (slot << shift) | (entry.item & low_bits)};
            }
        }
        if (!section_begin.empty()) section_begin.back() = static_cast<std::uint32_t>(write);
        list.resize(write);
    }

    /// DIS on every section, with the increments the controller chose.
    DisWork sort() {
        DisWork work;
        const int increments = dis.increments();
        for (std::size_t j = 0; j + 1 < section_begin.size(); ++j) {
            const std::span<Entry> section(list.data() + section_begin[j], section_begin[j + 1] - section_begin[j]);
            work += diminishing_increment_sort<Real>(section, increments);
        }
        return work;
    }

    /// The axial cut: every section into `cuts` segments of (nearly) equal length, each but a
    /// section's last at least `min_length` long on the axis; `segment_of` (the index array, by
    /// item id) is filled for this level's items.
    void cut(SegmentId cuts, std::vector<SegmentId>& segment_of, Real min_length = 0) {
        segment_of.resize(list.size());
        segment_begin.clear();
        const std::size_t sections = section_begin.size() - 1;
        segment_begin.reserve(sections * cuts + 1);
        for (std::size_t j = 0; j < sections; ++j) {
            const std::uint32_t first = section_begin[j];
            const std::span<const Entry> section(list.data() + first, section_begin[j + 1] - first);
            cut_section<Real>(section, first, cuts, static_cast<SegmentId>(j * cuts), segment_of, segment_begin,
                              min_length);
        }
        segment_begin.push_back(static_cast<std::uint32_t>(list.size()));
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return list.capacity() * sizeof(Entry) +
               (section_begin.capacity() + segment_begin.capacity()) * sizeof(std::uint32_t);
    }
};

}  // namespace smb::detail
