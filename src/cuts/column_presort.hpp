// SPDX-License-Identifier: MIT
#pragma once
// The boxes copied grouped by column again while they move across cells at every step (the
// paper's Λ = 0.1: every box jumps up to a tenth of the scene).
//
// Last step's cell order (cell_order.hpp) is this step's only while few boxes changed cell. Where
// most did, each column's boxes lie all over the ordered copy, and every later pass misses the
// cache on nearly every box. The detection then copies the boxes as a cold one does
// (CellOrder::copy_by_column()), reading the caller's boxes in order. Where boxes keep their
// cells, last step's order is that already (and x-sorted), so the regrouped copy starts only when
// the first level's hints miss on more than tuning::column_copy_start_misses of the boxes, and
// stops when fewer than tuning::column_copy_stop_changed of a sample changed column since the
// last one. Only speed depends on it: the order is any order of the slots.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/held_box.hpp"
#include "core/tuning.hpp"
#include "cuts/cut_tree.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim, std::floating_point Input>
class ColumnPresort {
public:
    /// After a detection that followed last step's order: the share of the first level's entries
    /// whose segment the hint missed.
    void judge(double first_level_misses) noexcept {
        if (first_level_misses > tuning::column_copy_start_misses) sorting_ = true;
    }

    /// Whether the next detection copies the boxes grouped by column (copy_by_column()).
    [[nodiscard]] bool sorting() const noexcept { return sorting_; }

    /// Forgets the columns (new planes, a new origin): the next judgement decides afresh.
    void forget() {
        sorting_ = false;
        std::vector<std::uint32_t>().swap(columns_);
    }

    /// Before a detection that copies by column: the columns of a sample of `input` (one box in
    /// tuning::column_copy_sample_stride), each compared with the same slot's at the last call (a
    /// slot renumbered or arrived since compares against another box's or none: a few, and only
    /// speed depends on it). Stops the regrouped copy from the next detection on once too few
    /// changed.
    void note_columns(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin,
                      const CutTree<Real, Dim>& cuts) {
        constexpr std::size_t stride = tuning::column_copy_sample_stride;
        const std::size_t samples = (input.size() + stride - 1) / stride;
        const std::size_t compared = std::min(columns_.size(), samples);
        columns_.resize(samples);
        std::size_t changed = 0;
        for (std::size_t i = 0; i < samples; ++i) {
            const std::uint32_t column = cuts.column_of(held_as<Real>(input[i * stride], origin));
            changed += i < compared && columns_[i] != column ? 1U : 0U;
            columns_[i] = column;
        }
        if (compared > 0 &&
            static_cast<double>(changed) < tuning::column_copy_stop_changed * static_cast<double>(compared))
            forget();
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept { return columns_.capacity() * sizeof(std::uint32_t); }

private:
    bool sorting_ = false;
    std::vector<std::uint32_t> columns_;  // per sampled slot: its column at the last regrouped copy
};

}  // namespace smb::detail
