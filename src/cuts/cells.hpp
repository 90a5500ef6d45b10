// SPDX-License-Identifier: MIT
#pragma once
// The cells of the persistent-cut pipeline's last regrouping: which cells a box covers, and which
// boxes registered there overlap a query box. The oversized boxes' check asks them, and so does
// the skin list, for the neighbours of a box that left its skin, without a detection of its own.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "cuts/cell_floor.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/cut_tree.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// Where the check of columns swept on x writes each cell's entries back in x order and the
/// bound on their x extent (Cells::widest); empty where the cells are not columns.
template <std::floating_point Real>
struct SweptColumns {
    std::span<Position> entries;
    std::span<Real> widest;
};

/// A view of the cells: valid while the regrouping that built them and the cuts are unchanged.
template <std::floating_point Real, int Dim>
struct Cells {
    const CutTree<Real, Dim>* cuts = nullptr;
    std::span<const Position> entries;     // the positions registered in each cell, cell by cell
    std::span<const std::uint32_t> begin;  // cell c holds entries [begin[c], begin[c + 1])
    /// Where the cells are columns swept on x: cell c's entries are in order of min x, and no
    /// box of it reaches further than widest[c] along x. Empty where the cells are unsorted.
    std::span<const Real> widest;

    static constexpr int axis_of_level(int level) noexcept { return CutTree<Real, Dim>::axis_of_level(level); }

    /// The lower planes of `cell` on every axis.
    [[nodiscard]] CellFloor<Real, Dim> floor_of(std::size_t cell) const {
        CellFloor<Real, Dim> floor{};
        std::size_t group = cell;
        for (int level = Dim - 1; level >= 0; --level) {
            const std::uint32_t k = cuts->segments(level);
            const auto segment = static_cast<std::uint32_t>(group % k);
            group /= k;
            floor[axis_of_level(level)] = cuts->lower(level, group, segment);
        }
        return floor;
    }

    /// Calls visit(cell, floor) for every cell whose segments `box` touches on every level.
    template <class Visit>
    void for_each_covering(const Box<Real, Dim>& box, Visit&& visit) const {
        CellFloor<Real, Dim> floor{};
        auto descend = [&](auto& self, int level, std::size_t group) -> void {
            if (level == Dim) {
                visit(group, floor);
                return;
            }
            const int axis = axis_of_level(level);
            const std::span<const Real> planes = cuts->cuts(level, group);
            const std::uint32_t lo = segment_of(planes, box.min[axis]);
            const std::uint32_t hi = segment_of(planes, box.max[axis]);
            for (std::uint32_t s = lo; s <= hi; ++s) {
                floor[axis] = cuts->lower(level, group, s);
                self(self, level + 1, group * cuts->segments(level) + s);
            }
        };
        descend(descend, 0, 0);
    }

    /// Calls visit(position) for every box registered in the cells `query` covers whose box in
    /// `boxes` overlaps `query`, once: a box registered in several of those cells is visited by the
    /// cell holding the lower corner of the two boxes' intersection (the cells' own rule: every box
    /// registered in a cell, and `query`, have min below the cell's upper plane on every axis).
    template <class Visit>
    void for_each_box_overlapping(const Box<Real, Dim>& query, std::span<const Box<Real, Dim>> boxes,
                                  Visit&& visit) const {
        for_each_covering(query, [&](std::size_t cell, const CellFloor<Real, Dim>& floor) {
            std::uint32_t first = begin[cell];
            const std::uint32_t last = begin[cell + 1];
            if (!widest.empty()) {
                // A box that reaches query.min x has min x >= query.min x - widest; rounded
                // down, the bound skips no such box.
                const Real from = std::nextafter(query.min[0] - widest[cell], -std::numeric_limits<Real>::infinity());
                first = static_cast<std::uint32_t>(
                    std::partition_point(entries.begin() + first, entries.begin() + last,
                                         [&](Position position) { return boxes[position].min[0] < from; }) -
                    entries.begin());
            }
            for (std::uint32_t i = first; i < last; ++i) {
                const Box<Real, Dim>& box = boxes[entries[i]];
                if (!widest.empty() && box.min[0] > query.max[0]) break;  // and every later one
                if (!overlaps(query, box)) continue;
                bool owned = true;
                for (int axis = 0; axis < Dim; ++axis)
                    owned = owned && (query.min[axis] >= floor[axis] || box.min[axis] >= floor[axis]);
                if (owned) visit(entries[i]);
            }
        });
    }

    /// Asserts that every box not `oversized` is registered in exactly the cells it covers.
    void check_registrations(std::span<const Box<Real, Dim>> boxes, std::span<const std::uint8_t> oversized) const {
        std::vector<std::uint32_t> registered(boxes.size(), 0);
        for (std::size_t cell = 0; cell + 1 < begin.size(); ++cell) {
            for (std::uint32_t i = begin[cell]; i < begin[cell + 1]; ++i) {
                SMB_ASSERT(!oversized[entries[i]], "an oversized box is in a cell");
                ++registered[entries[i]];
            }
        }
        for (std::size_t position = 0; position < boxes.size(); ++position) {
            if (oversized[position]) continue;
            std::uint32_t covered = 0;
            for_each_covering(boxes[position], [&](std::size_t cell, const CellFloor<Real, Dim>&) {
                ++covered;
                const auto* first = entries.data() + begin[cell];
                const auto* last = entries.data() + begin[cell + 1];
                SMB_ASSERT(std::find(first, last, static_cast<Position>(position)) != last,
                           "a box misses a cell it covers");
            });
            SMB_ASSERT(covered == registered[position], "a box is in a cell it does not cover");
        }
    }
};

}  // namespace smb::detail
