// SPDX-License-Identifier: MIT
#pragma once
// Before a two-set detection: which boxes of each set could overlap a box of the other one.
// Detecting the union of both sets spends its time on every box and on the pairs within each
// set too; a box that cannot meet the other set is better left out before the detection.
// Two cheap filters, both conservative (a box that overlaps a box of the other set is never
// left out), so the pairs stay exact:
//  1. the region: both sets' bounding boxes intersected; a box outside it meets nothing;
//  2. a coarse grid over that region, about one cell per box of the larger set: the cells the
//     smaller set touches are marked, the larger set keeps only its boxes that touch a marked
//     cell, and then the smaller set keeps only its boxes that touch a cell marked by what the
//     larger set kept.
// Where the sets are mixed evenly (two layers over the same land) nothing is left out and the
// filters cost two passes over the boxes; where one set is small or lies in a thin layer of
// the other (particles on a floor, in a container) most of the larger set is left out.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/scene_bounds.hpp"
#include "core/tuning.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// The indices of each set's boxes that the filters keep, in increasing order.
struct KeptBoxes {
    std::vector<std::size_t> first;
    std::vector<std::size_t> second;
};

template <std::floating_point Real, int Dim>
class SetCull {
public:
    using box_type = Box<Real, Dim>;

    /// Boxes must be valid (finite, min <= max).
    static KeptBoxes keep(std::span<const box_type> first, std::span<const box_type> second) {
        KeptBoxes kept;
        if (first.empty() || second.empty()) return kept;
        SetCull cull;
        if (!cull.intersect_bounds(first, second)) return kept;
        kept.first = cull.inside_region(first);
        kept.second = cull.inside_region(second);
        if (kept.first.empty() || kept.second.empty()) return {};
        const bool first_smaller = kept.first.size() < kept.second.size();
        auto& small = first_smaller ? kept.first : kept.second;
        auto& large = first_smaller ? kept.second : kept.first;
        const auto small_boxes = first_smaller ? first : second;
        const auto large_boxes = first_smaller ? second : first;
        // About one cell per box of the larger set, so that its boxes touch a few cells each and
        // the smaller set marks only the cells near it. Marking by a large box costs as many
        // cells as it covers: past a few passes over the boxes, a grid half as fine is tried,
        // and with none left the grid is given up (what the region kept stays).
        constexpr std::size_t cap = Dim == 2 ? tuning::join_cull_cells_2d : tuning::join_cull_cells_3d;
        auto per_axis = static_cast<std::size_t>(std::pow(static_cast<double>(large.size()), 1.0 / Dim));
        std::size_t budget = 0;
        for (per_axis = std::clamp<std::size_t>(per_axis, 1, cap);; per_axis /= 2) {
            if (per_axis < 2) return kept;
            cull.size_grid(per_axis);
            if (cull.cell_count_ <= 1) return kept;
            budget = 8 * (small.size() + large.size()) + cull.cell_count_;
            if (cull.mark(small_boxes, small, budget)) break;
        }
        // Sets mixed over the whole region (two layers of the same land) mark nearly every
        // cell: the grid would leave out little, so its other passes are not worth making.
        if (cull.marked_ * 10 >= cull.cell_count_ * 9) return kept;
        large = cull.touching_marks(large_boxes, large, budget);
        cull.marks_.assign(cull.cell_count_, 0);
        cull.marked_ = 0;
        if (!cull.mark(large_boxes, large, budget)) return kept;
        small = cull.touching_marks(small_boxes, small, budget);
        return kept;
    }

private:
    using Cells = std::array<std::array<std::size_t, 2>, Dim>;  // first and last cell per axis

    bool intersect_bounds(std::span<const box_type> first, std::span<const box_type> second) {
        const auto a = checked_bounds(first);
        const auto b = checked_bounds(second);
        for (int k = 0; k < Dim; ++k) {
            lo_[k] = static_cast<double>(std::max(a.lo[k], b.lo[k]));
            hi_[k] = static_cast<double>(std::min(a.hi[k], b.hi[k]));
            if (lo_[k] > hi_[k]) return false;
        }
        return true;
    }

    std::vector<std::size_t> inside_region(std::span<const box_type> boxes) const {
        std::vector<std::size_t> kept;
        kept.reserve(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            bool inside = true;
            for (int k = 0; k < Dim; ++k) inside = inside && boxes[i].min[k] <= hi_[k] && lo_[k] <= boxes[i].max[k];
            if (inside) kept.push_back(i);
        }
        return kept;
    }

    void size_grid(std::size_t per_axis) {
        cell_count_ = 1;
        marked_ = 0;
        for (int k = 0; k < Dim; ++k) {
            const double extent = hi_[k] - lo_[k];
            // A flat or overflowing extent puts everything in one cell on that axis.
            scale_[k] = extent > 0 && std::isfinite(extent) ? static_cast<double>(per_axis) / extent : 0.0;
            if (!std::isfinite(scale_[k])) scale_[k] = 0.0;
            axis_cells_[k] = scale_[k] > 0 ? per_axis : 1;
            cell_count_ *= axis_cells_[k];
        }
        marks_.assign(cell_count_, 0);
    }

    // Monotone in x (a subtraction, a product by a positive number, a floor and a clamp all
    // keep order), so two boxes that overlap on an axis get cell ranges that overlap: the
    // filter never leaves out a pair, whatever the rounding.
    std::size_t cell_of(double x, int k) const {
        const double t = (x - lo_[k]) * scale_[k];
        if (!(t > 0)) return 0;
        const auto last = axis_cells_[k] - 1;
        return t >= static_cast<double>(last) ? last : static_cast<std::size_t>(t);
    }

    Cells cells_of(const box_type& box) const {
        Cells cells;
        for (int k = 0; k < Dim; ++k) cells[k] = {cell_of(box.min[k], k), cell_of(box.max[k], k)};
        return cells;
    }

    std::size_t flat_index(const std::array<std::size_t, Dim>& cell) const {
        std::size_t index = 0;
        for (int k = Dim - 1; k >= 0; --k) index = index * axis_cells_[k] + cell[k];
        return index;
    }

    /// Calls `visit(flat index)` for every cell of `cells` until it returns true; true if it did.
    template <class Visit>
    bool any_cell(const Cells& cells, Visit visit) const {
        std::array<std::size_t, Dim> cell;
        for (int k = 0; k < Dim; ++k) cell[k] = cells[k][0];
        while (true) {
            if (visit(flat_index(cell))) return true;
            int k = 0;
            while (k < Dim && cell[k] == cells[k][1]) {
                cell[k] = cells[k][0];
                ++k;
            }
            if (k == Dim) return false;
            ++cell[k];
        }
    }

    /// Marks the cells `boxes[kept]` touch; false (marks incomplete) past `budget` cells.
    bool mark(std::span<const box_type> boxes, const std::vector<std::size_t>& kept, std::size_t budget) {
        std::size_t spent = 0;
        for (const std::size_t i : kept) {
            const Cells cells = cells_of(boxes[i]);
            spent += covered(cells);
            if (spent > budget) return false;
            any_cell(cells, [this](std::size_t cell) {
                marked_ += marks_[cell] == 0 ? 1 : 0;
                marks_[cell] = 1;
                return false;
            });
        }
        return true;
    }

    /// The boxes of `kept` that touch a marked cell. Past `budget` cells looked at, the rest
    /// are kept unchecked (large boxes over unmarked cells would cost their every cell).
    std::vector<std::size_t> touching_marks(std::span<const box_type> boxes, const std::vector<std::size_t>& kept,
                                            std::size_t budget) const {
        std::vector<std::size_t> touching;
        touching.reserve(kept.size());
        std::size_t spent = 0;
        for (const std::size_t i : kept) {
            const Cells cells = cells_of(boxes[i]);
            spent += covered(cells);
            if (spent > budget || any_cell(cells, [this](std::size_t cell) { return marks_[cell] != 0; }))
                touching.push_back(i);
        }
        return touching;
    }

    static std::size_t covered(const Cells& cells) {
        std::size_t count = 1;
        for (int k = 0; k < Dim; ++k) count *= cells[k][1] - cells[k][0] + 1;
        return count;
    }

    std::array<double, Dim> lo_{};
    std::array<double, Dim> hi_{};
    std::array<double, Dim> scale_{};
    std::array<std::size_t, Dim> axis_cells_{};
    std::size_t cell_count_ = 1;
    std::size_t marked_ = 0;  ///< cells marked so far
    std::vector<std::uint8_t> marks_;
};

}  // namespace smb::detail
