// SPDX-License-Identifier: MIT
#include "smb/workload/reference_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace smb::workload {

namespace {

// Method. Boxes go into every cell of a uniform grid they touch; a pair is examined in every cell
// both touch but reported only in the cell that holds the lower corner of their intersection,
// max(a.min, b.min). That point lies in both (closed) boxes and the cell of a coordinate is a
// monotone function of it, so the owner cell is among the cells of each box: every overlapping
// pair is reported exactly once, whatever the cell size. The cell size only sets the cost. It is
// the largest extent among the "small" boxes, so those touch at most two cells per axis; boxes
// more than twice the 99th percentile of extents are "big" and stay out of the grid.

constexpr double big_box_percentile = 0.99;
constexpr double big_box_factor = 2.0;

using Member = std::uint32_t;

template <std::floating_point Real, int Dim>
class GridPairFinder {
public:
    using box_type = Box<Real, Dim>;
    using CellCoords = std::array<std::size_t, Dim>;
    struct CellRange {
        CellCoords first{};
        CellCoords last{};
    };

    GridPairFinder(std::span<const BoxId> ids, std::span<const box_type> boxes) : ids_(ids), boxes_(boxes) {}

    std::vector<Pair> run() {
        split_by_size();
        if (!small_.empty()) {
            choose_grid();
            fill_cells();
            check_small_pairs();
            check_big_against_small();
        }
        check_big_pairs();
        sort_pairs(pairs_);
        return std::move(pairs_);
    }

private:
    static double extent_of(const box_type& box) {
        double extent = 0;
        for (int k = 0; k < Dim; ++k)
            extent = std::max(extent, static_cast<double>(box.max[k]) - static_cast<double>(box.min[k]));
        return extent;
    }

    void split_by_size() {
        const std::size_t n = boxes_.size();
        std::vector<double> extents(n);
        for (std::size_t i = 0; i < n; ++i) extents[i] = extent_of(boxes_[i]);
        std::vector<double> sorted = extents;
        const auto rank = static_cast<std::size_t>(big_box_percentile * static_cast<double>(n - 1));
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(rank), sorted.end());
        const double threshold = big_box_factor * sorted[rank];
        for (std::size_t i = 0; i < n; ++i) {
            if (extents[i] > threshold) {
                big_.push_back(static_cast<Member>(i));
            } else {
                small_.push_back(static_cast<Member>(i));
                largest_small_extent_ = std::max(largest_small_extent_, extents[i]);
            }
        }
    }

    void choose_grid() {
        low_.fill(std::numeric_limits<double>::infinity());
        std::array<double, Dim> high;
        high.fill(-std::numeric_limits<double>::infinity());
        for (const Member i : small_) {
            for (int k = 0; k < Dim; ++k) {
                low_[k] = std::min(low_[k], static_cast<double>(boxes_[i].min[k]));
                high[k] = std::max(high[k], static_cast<double>(boxes_[i].max[k]));
            }
        }
        double widest = 0;
        for (int k = 0; k < Dim; ++k) widest = std::max(widest, high[k] - low_[k]);

        cell_size_ = largest_small_extent_;
        if (!(cell_size_ > 0)) cell_size_ = widest > 0 ? widest / static_cast<double>(small_.size()) : 1.0;
        // Tiny boxes spread over a huge space would ask for far more cells than boxes: coarsen.
        const double cell_limit = 2.0 * static_cast<double>(small_.size()) + 64;
        for (;;) {
            std::array<double, Dim> per_axis{};
            double cells = 1;
            for (int k = 0; k < Dim; ++k) {
                per_axis[k] = std::floor((high[k] - low_[k]) / cell_size_) + 1;
                cells *= per_axis[k];
            }
            if (cells <= cell_limit) {
                for (int k = 0; k < Dim; ++k) cells_per_axis_[k] = static_cast<std::size_t>(per_axis[k]);
                return;
            }
            cell_size_ *= 2;
        }
    }

    std::size_t cell_coord(double value, int k) const {
        const double t = (value - low_[k]) / cell_size_;
        if (!(t > 0)) return 0;
        const double last = static_cast<double>(cells_per_axis_[k] - 1);
        return t >= last ? cells_per_axis_[k] - 1 : static_cast<std::size_t>(t);
    }

    CellRange cell_range(const box_type& box) const {
        CellRange range;
        for (int k = 0; k < Dim; ++k) {
            range.first[k] = cell_coord(static_cast<double>(box.min[k]), k);
            range.last[k] = cell_coord(static_cast<double>(box.max[k]), k);
        }
        return range;
    }

    std::size_t flat_index(const CellCoords& coords) const {
        std::size_t index = 0;
        for (int k = Dim - 1; k >= 0; --k) index = index * cells_per_axis_[k] + coords[k];
        return index;
    }

    template <typename Visit>
    void for_each_cell(const CellRange& range, Visit&& visit) const {
        CellCoords coords = range.first;
        for (;;) {
            visit(flat_index(coords), coords);
            int k = 0;
            while (k < Dim && coords[k] == range.last[k]) {
                coords[k] = range.first[k];
                ++k;
            }
            if (k == Dim) return;
            ++coords[k];
        }
    }

    void fill_cells() {
        std::size_t cell_count = 1;
        for (int k = 0; k < Dim; ++k) cell_count *= cells_per_axis_[k];
        cell_start_.assign(cell_count + 1, 0);
        for (const Member i : small_)
            for_each_cell(cell_range(boxes_[i]), [&](std::size_t cell, const CellCoords&) { ++cell_start_[cell + 1]; });
        for (std::size_t c = 0; c < cell_count; ++c) cell_start_[c + 1] += cell_start_[c];
        members_.resize(cell_start_.back());
        std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
        for (const Member i : small_)
            for_each_cell(cell_range(boxes_[i]),
                          [&](std::size_t cell, const CellCoords&) { members_[fill[cell]++] = i; });
    }

    bool owned_by(const box_type& a, const box_type& b, const CellCoords& cell) const {
        for (int k = 0; k < Dim; ++k) {
            const double corner = std::max(static_cast<double>(a.min[k]), static_cast<double>(b.min[k]));
            if (cell_coord(corner, k) != cell[k]) return false;
        }
        return true;
    }

    void report(Member i, Member j) { pairs_.push_back({std::min(ids_[i], ids_[j]), std::max(ids_[i], ids_[j])}); }

    void check_small_pairs() {
        CellRange everything;
        for (int k = 0; k < Dim; ++k) everything.last[k] = cells_per_axis_[k] - 1;
        for_each_cell(everything, [&](std::size_t cell, const CellCoords& coords) {
            const std::size_t begin = cell_start_[cell];
            const std::size_t end = cell_start_[cell + 1];
            for (std::size_t p = begin; p < end; ++p) {
                const box_type& a = boxes_[members_[p]];
                for (std::size_t q = p + 1; q < end; ++q) {
                    const box_type& b = boxes_[members_[q]];
                    if (overlaps(a, b) && owned_by(a, b, coords)) report(members_[p], members_[q]);
                }
            }
        });
    }

    // A big box visits the grid cells it covers (clamped to the grid); the owner-cell rule still
    // holds because the clamped cell function stays monotone.
    void check_big_against_small() {
        for (const Member i : big_) {
            const box_type& a = boxes_[i];
            for_each_cell(cell_range(a), [&](std::size_t cell, const CellCoords& coords) {
                for (std::size_t p = cell_start_[cell]; p < cell_start_[cell + 1]; ++p) {
                    const box_type& b = boxes_[members_[p]];
                    if (overlaps(a, b) && owned_by(a, b, coords)) report(i, members_[p]);
                }
            });
        }
    }

    void check_big_pairs() {
        for (std::size_t p = 0; p < big_.size(); ++p)
            for (std::size_t q = p + 1; q < big_.size(); ++q)
                if (overlaps(boxes_[big_[p]], boxes_[big_[q]])) report(big_[p], big_[q]);
    }

    std::span<const BoxId> ids_;
    std::span<const box_type> boxes_;
    std::vector<Member> small_;
    std::vector<Member> big_;
    double largest_small_extent_ = 0;
    std::array<double, Dim> low_{};
    double cell_size_ = 1;
    CellCoords cells_per_axis_{};
    std::vector<std::size_t> cell_start_;
    std::vector<Member> members_;
    std::vector<Pair> pairs_;
};

}  // namespace

template <std::floating_point Real, int Dim>
std::vector<Pair> grid_pairs(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes) {
    if (ids.size() != boxes.size()) throw std::invalid_argument("grid_pairs: ids and boxes differ in length");
    if (boxes.size() > std::numeric_limits<Member>::max()) throw std::length_error("grid_pairs: too many boxes");
    for (const auto& box : boxes)
        if (!is_valid(box)) throw std::invalid_argument("grid_pairs: invalid box");
    if (boxes.size() < 2) return {};
    return GridPairFinder<Real, Dim>(ids, boxes).run();
}

template std::vector<Pair> grid_pairs<float, 2>(std::span<const BoxId>, std::span<const Box<float, 2>>);
template std::vector<Pair> grid_pairs<double, 2>(std::span<const BoxId>, std::span<const Box<double, 2>>);
template std::vector<Pair> grid_pairs<float, 3>(std::span<const BoxId>, std::span<const Box<float, 3>>);
template std::vector<Pair> grid_pairs<double, 3>(std::span<const BoxId>, std::span<const Box<double, 3>>);

}  // namespace smb::workload
