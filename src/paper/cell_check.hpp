// SPDX-License-Identifier: MIT
#pragma once
// The cell check of the paper's Section 2.4 (8) and steps 13-15 of its Section 3. Inside one
// cell every box present is known by its local number (global_local_map.hpp). For each axis the
// cell's list of corners, sorted on that axis, is swept once: a box opens at its first min
// corner and closes at its first max corner; every box it meets open overlaps it on that axis,
// and the pair's flag in an m x m byte matrix gets that axis' bit. A pair whose flag holds every
// axis' bit is a contact, reported unless the mask says it was checked in an earlier cell.
//
// A box present in the cell without its min (or max) corner on some axis has that end in the
// previous (or next) segment of that axis: its interval reaches past the cell's edge, so it is
// open from the start of the sweep (or never closes). Because cuts fall only between distinct
// coordinates, this reproduces the exact closed overlap of the full intervals.
//
// The matrix costs m^2 bytes. A cell can be far more populated than the cut aims for when many
// boxes share one coordinate (cuts never split a value), e.g. thousands of identical boxes; such
// a cell is checked by the sweep on the deepest axis alone with the other axes compared directly,
// which is exact too and costs what the output costs.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/tuning.hpp"
#include "paper/axis_entry.hpp"
#include "paper/global_local_map.hpp"
#include "paper/mask_array.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class CellChecker {
public:
    /// Above this many boxes a cell is checked without the flag matrix.
    static constexpr std::size_t kMatrixMaxBoxes = tuning::paper_matrix_max_boxes;

    /// The sorted corner lists of one cell: levels 0 .. Dim-2 regrouped from the upper lists,
    /// and the cell's own range of the deepest list.
    struct CellLists {
        std::array<std::span<const Item>, Dim - 1> upper;
        std::span<const AxisEntry<Real>> deepest;
    };

    /// Checks one cell. `report(slot_a, slot_b)` receives each new contact.
    template <class Report>
    void check(const CellLists& cell, const std::vector<std::uint8_t>& oversized, std::span<const Box<Real, Dim>> boxes,
               GlobalLocalMap& map, const MaskArray& mask, Report&& report) {
        build_local_map(cell.deepest, oversized, map);
        const std::size_t m = map.size();
        if (m >= 2) {
            if (m <= kMatrixMaxBoxes) {
                check_with_flag_matrix(cell, map, mask, report);
            } else {
                check_with_direct_tests(cell, boxes, map, mask, report);
            }
        }
    }

    /// The m x m flag matrix of the last cell checked with it (row a, column b > a), as the
    /// paper's example draws it.
    [[nodiscard]] std::span<const std::uint8_t> flag_matrix() const noexcept { return flags_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return flags_.capacity() + open_.capacity() + present_min_.capacity() +
               (active_.capacity() + position_.capacity()) * sizeof(std::uint32_t);
    }

private:
    static constexpr Item kCornerMask = (Item{1} << Dim) - 1;
    static constexpr std::uint8_t kAllAxes = static_cast<std::uint8_t>((1U << Dim) - 1);

    static constexpr Item slot_of_corner(Item corner) noexcept { return corner >> Dim; }
    static constexpr Item end_on_level(Item corner, int level) noexcept { return (corner >> (Dim - 1 - level)) & 1U; }

    void build_local_map(std::span<const AxisEntry<Real>> deepest, const std::vector<std::uint8_t>& oversized,
                         GlobalLocalMap& map) {
        present_min_.clear();
        for (const auto& entry : deepest) {
            const Item slot = slot_of_corner(entry.item);
            if (oversized[slot]) continue;
            const std::uint32_t local = map.local(slot);
            if (local == present_min_.size()) present_min_.push_back(0);
            std::uint8_t min_ends = 0;
            for (int level = 0; level < Dim; ++level) {
                if (end_on_level(entry.item, level) == 0)
                    min_ends = static_cast<std::uint8_t>(min_ends | (1U << level));
            }
            present_min_[local] = static_cast<std::uint8_t>(present_min_[local] | min_ends);
        }
    }

    /// One sweep over a cell's list on the axis of `level`; `overlap(a, b)` for every pair of
    /// local boxes whose intervals on that axis overlap, each pair once.
    template <class CornerAt, class Overlap>
    void sweep(std::size_t count, CornerAt corner_at, int level, const GlobalLocalMap& map, Overlap&& overlap) {
        const std::size_t m = map.size();
        open_.assign(m, kNotYet);
        position_.resize(m);
        active_.clear();
        auto open = [&](std::uint32_t box) {
            for (const std::uint32_t other : active_) overlap(other, box);
            position_[box] = static_cast<std::uint32_t>(active_.size());
            active_.push_back(box);
            open_[box] = kOpen;
        };
        for (std::uint32_t box = 0; box < m; ++box) {
            if ((present_min_[box] & (1U << level)) == 0) open(box);
        }
        for (std::size_t i = 0; i < count; ++i) {
            const Item corner = corner_at(i);
            const std::uint32_t box = map.find(slot_of_corner(corner));
            if (box == GlobalLocalMap::kAbsent) continue;  // oversized: checked elsewhere
            if (end_on_level(corner, level) == 0) {
                if (open_[box] == kNotYet) open(box);
            } else if (open_[box] == kOpen) {
                const std::uint32_t last = active_.back();
                active_[position_[box]] = last;
                position_[last] = position_[box];
                active_.pop_back();
                open_[box] = kClosed;
            }
        }
    }

    template <class Report>
    void check_with_flag_matrix(const CellLists& cell, const GlobalLocalMap& map, const MaskArray& mask,
                                Report& report) {
        const std::size_t m = map.size();
        flags_.assign(m * m, 0);
        for (int level = 0; level + 1 < Dim; ++level) {
            const auto list = cell.upper[static_cast<std::size_t>(level)];
            const auto bit = static_cast<std::uint8_t>(1U << level);
            sweep(
                list.size(), [&](std::size_t i) { return list[i]; }, level, map,
                [&](std::uint32_t a, std::uint32_t b) { flags_[std::min(a, b) * m + std::max(a, b)] |= bit; });
        }
        constexpr auto deepest_bit = static_cast<std::uint8_t>(1U << (Dim - 1));
        sweep(
            cell.deepest.size(), [&](std::size_t i) { return cell.deepest[i].item; }, Dim - 1, map,
            [&](std::uint32_t a, std::uint32_t b) {
                std::uint8_t& flag = flags_[std::min(a, b) * m + std::max(a, b)];
                flag = static_cast<std::uint8_t>(flag | deepest_bit);
                if (flag != kAllAxes) return;
                const std::uint32_t slot_a = map.global(a);
                const std::uint32_t slot_b = map.global(b);
                if (!mask.already_checked(slot_a, slot_b)) report(slot_a, slot_b);
            });
    }

    template <class Report>
    void check_with_direct_tests(const CellLists& cell, std::span<const Box<Real, Dim>> boxes,
                                 const GlobalLocalMap& map, const MaskArray& mask, Report& report) {
        sweep(
            cell.deepest.size(), [&](std::size_t i) { return cell.deepest[i].item; }, Dim - 1, map,
            [&](std::uint32_t a, std::uint32_t b) {
                const std::uint32_t slot_a = map.global(a);
                const std::uint32_t slot_b = map.global(b);
                if (mask.already_checked(slot_a, slot_b)) return;
                if (overlaps(boxes[slot_a], boxes[slot_b])) report(slot_a, slot_b);
            });
    }

    static constexpr std::uint8_t kNotYet = 0;
    static constexpr std::uint8_t kOpen = 1;
    static constexpr std::uint8_t kClosed = 2;

    std::vector<std::uint8_t> flags_;        // the cell's m x m flag matrix (upper triangle used)
    std::vector<std::uint8_t> present_min_;  // per local box: bit l = its min end on level l is in the cell
    std::vector<std::uint8_t> open_;
    std::vector<std::uint32_t> active_;
    std::vector<std::uint32_t> position_;
};

}  // namespace smb::detail
