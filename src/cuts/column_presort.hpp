// SPDX-License-Identifier: MIT
#pragma once
// The order of the boxes sorted again by column before the copy, while the boxes move across
// cells at every step (the paper's Λ = 0.1: every box jumps up to a tenth of the scene).
//
// The persistent cuts read the boxes in last step's cell order (cell_order.hpp), which is the
// order of this step's cells only while few boxes changed cell. Where most did, each column's
// boxes lie all over the ordered copy, and every pass after the copy (the levels and the cell
// check) misses the cache on nearly every box. A counting sort of the slots by the column that
// holds each box's lower corner, against the kept planes, costs one streaming pass over the
// caller's boxes and one scatter of the slots; the copy then lays each column out in one run.
// Where boxes keep their cells, last step's order is already that (and x-sorted within each
// column), so the sort is left out: it starts when the first level's hints miss on a quarter
// of the boxes, and stops when fewer than half of the boxes changed column since the last sort.
// Only speed depends on it: the order is any order of the slots.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/bulk_vector.hpp"
#include "core/held_box.hpp"
#include "core/slot_renumbering.hpp"
#include "cuts/cut_tree.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim, std::floating_point Input>
class ColumnPresort {
public:
    /// After a detection that followed last step's order: the share of the first level's entries
    /// whose segment the hint missed.
    void judge(double first_level_misses) noexcept {
        if (first_level_misses > kStartMisses) sorting_ = true;
    }

    /// Whether the next detection sorts the order by column first.
    [[nodiscard]] bool sorting() const noexcept { return sorting_; }

    /// Forgets the columns (new planes, a new origin): the next judgement decides afresh.
    void forget() {
        sorting_ = false;
        std::vector<std::uint32_t>().swap(columns_);
        std::vector<std::uint32_t>().swap(counts_);
    }

    /// Rewrites `order` (every slot of `input` once) as the slots grouped by the column of their
    /// box's lower corner, in slot order within a column.
    void sort(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin,
              const CutTree<Real, Dim>& cuts, BulkVector<Slot>& order) {
        const std::size_t n = input.size();
        const std::size_t column_count = cuts.groups(Dim - 1);
        // Slots a removal renumbered, or that arrived, compare against another box's column or
        // none: a few, and the share is a judgement of speed only.
        const std::size_t compared = std::min(columns_.size(), n);
        columns_.resize(n);
        counts_.assign(column_count + 1, 0);
        std::size_t changed = 0;
        for (std::size_t slot = 0; slot < n; ++slot) {
            const std::uint32_t column = column_of(input[slot], origin, cuts);
            changed += slot < compared && columns_[slot] != column ? 1U : 0U;
            columns_[slot] = column;
            ++counts_[column + 1];
        }
        for (std::size_t c = 1; c <= column_count; ++c) counts_[c] += counts_[c - 1];
        order.resize(n);
        for (std::size_t slot = 0; slot < n; ++slot) order[counts_[columns_[slot]]++] = static_cast<Slot>(slot);
        if (compared > 0 && static_cast<double>(changed) < kStopChanged * static_cast<double>(compared)) forget();
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (columns_.capacity() + counts_.capacity()) * sizeof(std::uint32_t);
    }

private:
    // A hint that misses on a quarter of the entries is the locator's own sign that the order
    // no longer follows the cells (group_locator.hpp). At 1M boxes in 3D the sort paid at
    // Λ = 0.1 (98% of the boxes change column a step: 180 against 250-270 ms), broke even at
    // Λ = 0.03 (76%) and lost a little at Λ = 0.01 (about 30%), where last step's order,
    // x-sorted within each column, serves the check better.
    static constexpr double kStartMisses = 0.25;
    static constexpr double kStopChanged = 0.5;

    /// The column (group of the deepest level's parent) holding the box's lower corner.
    [[nodiscard]] static std::uint32_t column_of(const Box<Input, Dim>& box, const std::array<Input, Dim>& origin,
                                                 const CutTree<Real, Dim>& cuts) noexcept {
        return cuts.column_of(held_as<Real>(box, origin));
    }

    bool sorting_ = false;
    std::vector<std::uint32_t> columns_;  // per slot: its column at the last sort
    std::vector<std::uint32_t> counts_;   // the counting sort's offsets, one per column
};

}  // namespace smb::detail
