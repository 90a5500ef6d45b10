// SPDX-License-Identifier: MIT
#pragma once
// The one grid of smb: a hierarchy of uniform grids, behind smb::BoxIndex (a World's queries)
// and the statics of a filtered World (filters/static_grid.hpp). Each box sits on the finest
// level whose cell is at least its largest extent, so it reaches at most one cell past the cell
// of its lower corner (its home cell). The boxes are sorted by (level, home cell): a cell's boxes
// are one contiguous run, and a row of cells along the first axis is one run too. A box query
// visits, on each level, the home cells from its lower corner less the level's widest box up to
// its upper corner, row by row, and reads each box once: no box is listed twice, and nothing is
// reported twice. A box too large for every level (the scene's extent overflows, or 64 levels do
// not reach it) sits on the coarsest, whose reach then covers it. The ray walk is in
// grid_ray.hpp.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/tuning.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// One level of the hierarchy: a grid over the scene's bounds with cells of side `side`.
template <int Dim>
struct GridLevel {
    double side = 1;
    double inv = 1;                     // 1 / side
    std::array<std::int64_t, Dim> n{};  // cells per axis
    std::size_t first_cell = 0;         // of this level in GridIndex::cell_start
    std::array<double, Dim> reach{};    // at least the widest box of the level, per axis
};

/// The cell of grid coordinate g on an axis of n cells. Clamping keeps the scene's boxes (which
/// lie inside the grid) in range and sends anything outside to the border cells; it is monotone,
/// which is what makes the box query exact.
inline std::int64_t clamped_cell(double g, std::int64_t n) noexcept {
    if (!(g >= 0)) return 0;
    if (g >= static_cast<double>(n)) return n - 1;
    return static_cast<std::int64_t>(g);
}

template <std::floating_point Real, int Dim>
class GridIndex {
public:
    using box_type = Box<Real, Dim>;

    // The state, read by the ray walk. Boxes and ids are in home-cell order (level, then the
    // cell of the lower corner).
    std::vector<box_type> boxes;
    std::vector<BoxId> ids;
    std::vector<GridLevel<Dim>> levels;     // the non-empty levels, finest first
    std::vector<std::uint32_t> cell_start;  // boxes of home cell c: [cell_start[c], cell_start[c+1])
    std::array<double, Dim> origin{};       // the scene's lower corner: the grids' origin
    std::array<double, Dim> upper{};        // the scene's upper corner

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return boxes.capacity() * sizeof(box_type) + ids.capacity() * sizeof(BoxId) +
               levels.capacity() * sizeof(GridLevel<Dim>) + cell_start.capacity() * sizeof(std::uint32_t);
    }

    [[nodiscard]] std::int64_t cell_of(double v, int k, const GridLevel<Dim>& level) const noexcept {
        return clamped_cell((v - origin[k]) * level.inv, level.n[k]);
    }

    /// The lowest home cell, on axis k, of a box of `level` that reaches down to v: its lower
    /// corner is at least v less the level's reach, rounded down here, and cell_of never
    /// decreases.
    [[nodiscard]] std::int64_t home_from(double v, int k, const GridLevel<Dim>& level) const noexcept {
        return cell_of(std::nextafter(v - level.reach[k], -std::numeric_limits<double>::infinity()), k, level);
    }

    /// Indexes boxes[i] under id_of(i) for every i with keep(i); the boxes must be valid.
    template <class IdOf, class Keep>
    void build(std::span<const box_type> input, IdOf id_of, Keep keep) {
        if (input.size() >= std::numeric_limits<std::uint32_t>::max())
            throw ArgumentError("BoxIndex: " + std::to_string(input.size()) + " boxes, more than 2^32 - 2");
        boxes.clear();
        ids.clear();
        boxes.reserve(input.size());
        ids.reserve(input.size());
        for (std::size_t i = 0; i < input.size(); ++i) {
            if (!keep(i)) continue;
            boxes.push_back(input[i]);
            ids.push_back(id_of(i));
        }
        index_boxes();
    }

    /// Calls emit(position) for every box overlapping q (closed overlap), each once.
    template <class Emit>
    void query_positions(const box_type& q, Emit&& emit) const {
        if (boxes.empty()) return;
        for (int k = 0; k < Dim; ++k) {
            if (q.min[k] > upper[k] || q.max[k] < origin[k]) return;
        }
        for (const GridLevel<Dim>& level : levels) {
            std::array<std::int64_t, Dim> lo{};
            std::array<std::int64_t, Dim> hi{};
            for (int k = 0; k < Dim; ++k) {
                lo[k] = home_from(static_cast<double>(q.min[k]), k, level);
                hi[k] = cell_of(static_cast<double>(q.max[k]), k, level);
            }
            for_rows(lo, hi, level, [&](std::size_t first_cell, std::size_t last_cell) {
                for (std::uint32_t p = cell_start[first_cell]; p < cell_start[last_cell + 1]; ++p) {
                    if (overlaps(q, boxes[p])) emit(p);
                }
            });
        }
    }

    /// Calls emit(id) for every box overlapping q, each once.
    template <class Emit>
    void query(const box_type& q, Emit&& emit) const {
        query_positions(q, [&](std::uint32_t p) { emit(ids[p]); });
    }

    /// Calls run(first, last) for every row of cells of `level` in [lo, hi] (inclusive): the
    /// cells first to last along the first axis.
    template <class Run>
    static void for_rows(const std::array<std::int64_t, Dim>& lo, const std::array<std::int64_t, Dim>& hi,
                         const GridLevel<Dim>& level, Run&& run) {
        const auto x0 = static_cast<std::size_t>(lo[0]);
        const auto x1 = static_cast<std::size_t>(hi[0]);
        if constexpr (Dim == 2) {
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
                const auto row = level.first_cell + static_cast<std::size_t>(y * level.n[0]);
                run(row + x0, row + x1);
            }
        } else {
            for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
                for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
                    const auto row = level.first_cell + static_cast<std::size_t>((z * level.n[1] + y) * level.n[0]);
                    run(row + x0, row + x1);
                }
            }
        }
    }

private:
    /// The finest cell side: the boxes' mean largest extent, made coarser until the finest grid
    /// has at most about 2N cells (so sparse scenes and point-like boxes cost O(N) memory).
    [[nodiscard]] double finest_side(double mean_extent, double span) const {
        const double cap = tuning::grid_cells_per_box * static_cast<double>(boxes.size()) + 16.0;
        if (!(span > 0) || !std::isfinite(span)) return 1;
        double side = mean_extent > 0 ? mean_extent : span / cap;
        side = std::max(side, span * 1e-12);
        // Subnormal scenes (a span near 1e-308) can round the side to 0, which no growth
        // below would leave: the whole span is one cell then.
        if (!(side > 0)) return span;
        for (;;) {
            double cells = 1;
            for (int k = 0; k < Dim; ++k) cells *= std::max(1.0, std::ceil((upper[k] - origin[k]) / side));
            if (cells <= cap) return side;
            side *= tuning::grid_side_growth;
        }
    }

    void index_boxes() {
        levels.clear();
        cell_start.clear();
        const std::size_t n = boxes.size();
        if (n == 0) return;
        origin.fill(std::numeric_limits<double>::infinity());
        upper.fill(-std::numeric_limits<double>::infinity());
        double extent_sum = 0;
        for (const box_type& b : boxes) {
            double e = 0;
            for (int k = 0; k < Dim; ++k) {
                origin[k] = std::min(origin[k], static_cast<double>(b.min[k]));
                upper[k] = std::max(upper[k], static_cast<double>(b.max[k]));
                e = std::max(e, static_cast<double>(b.max[k]) - static_cast<double>(b.min[k]));
            }
            extent_sum += e;
        }
        // Coordinates near the ends of double's range can make the scene's extent overflow: then
        // one cell holds everything (inv = 0 sends every coordinate to it), exact but unindexed.
        double span = 0;
        for (int k = 0; k < Dim; ++k) span = std::max(span, upper[k] - origin[k]);
        const bool finite_span = std::isfinite(span);  // no NaN: the bounds are finite
        double side0 = finite_span ? finest_side(extent_sum / static_cast<double>(n), span)
                                   : std::numeric_limits<double>::infinity();
        // A subnormal side has no finite inverse: the same single cell.
        if (!std::isfinite(1 / side0)) side0 = std::numeric_limits<double>::infinity();

        // Level of each box: the finest whose side is at least the box's largest extent, up to
        // the level of a single cell per axis.
        constexpr int kMaxLevels = 64;
        int top = 0;
        while (finite_span && top + 1 < kMaxLevels && std::ldexp(side0, top) < span) ++top;
        std::vector<std::uint8_t> level_of(n);
        std::array<std::size_t, kMaxLevels> per_level{};
        for (std::size_t i = 0; i < n; ++i) {
            double e = 0;
            for (int k = 0; k < Dim; ++k) e = std::max(e, static_cast<double>(boxes[i].max[k]) - boxes[i].min[k]);
            int l = 0;
            while (l < top && std::ldexp(side0, l) < e) ++l;
            level_of[i] = static_cast<std::uint8_t>(l);
            ++per_level[static_cast<std::size_t>(l)];
        }
        std::array<int, kMaxLevels> slot_of_level{};
        std::size_t cells = 0;
        for (int l = 0; l <= top; ++l) {
            slot_of_level[static_cast<std::size_t>(l)] = static_cast<int>(levels.size());
            if (per_level[static_cast<std::size_t>(l)] == 0) continue;
            GridLevel<Dim> level;
            level.side = std::ldexp(side0, l);
            level.inv = 1 / level.side;
            std::size_t count = 1;
            for (int k = 0; k < Dim; ++k) {
                const double across = std::ceil((upper[k] - origin[k]) * level.inv);
                level.n[k] = across >= 1 ? static_cast<std::int64_t>(across) : 1;  // (NaN: inv = 0, a single cell)
                count *= static_cast<std::size_t>(level.n[k]);
            }
            level.first_cell = cells;
            cells += count;
            levels.push_back(level);
        }

        // Counting sort of the boxes by (level, home cell); the counts become cell_start.
        if (cells >= std::numeric_limits<std::uint32_t>::max()) throw ArgumentError("BoxIndex: too many cells");
        std::vector<std::uint32_t> cell_key(n);
        cell_start.assign(cells + 1, 0);
        for (std::size_t i = 0; i < n; ++i) {
            auto& level = levels[static_cast<std::size_t>(slot_of_level[level_of[i]])];
            std::size_t c = 0;
            for (int k = Dim - 1; k >= 0; --k)
                c = c * static_cast<std::size_t>(level.n[k]) +
                    static_cast<std::size_t>(cell_of(boxes[i].min[k], k, level));
            for (int k = 0; k < Dim; ++k) {
                const double width = static_cast<double>(boxes[i].max[k]) - static_cast<double>(boxes[i].min[k]);
                level.reach[k] =
                    std::max(level.reach[k], std::nextafter(width, std::numeric_limits<double>::infinity()));
            }
            cell_key[i] = static_cast<std::uint32_t>(level.first_cell + c);
            ++cell_start[cell_key[i] + 1];
        }
        for (std::size_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
        std::vector<std::uint32_t> next(cell_start.begin(), cell_start.end() - 1);
        std::vector<box_type> sorted_boxes(n);
        std::vector<BoxId> sorted_ids(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t to = next[cell_key[i]]++;
            sorted_boxes[to] = boxes[i];
            sorted_ids[to] = ids[i];
        }
        boxes.swap(sorted_boxes);
        ids.swap(sorted_ids);
    }
};

}  // namespace smb::detail
