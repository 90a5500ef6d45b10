// SPDX-License-Identifier: MIT
#pragma once
// The uniform grid of the comparison, rebuilt from scratch on every call and written to be as
// fast as a grid gets on boxes of similar size:
//
// - Each box is stored once, in the cell of its lower corner. The cells are anisotropic: along x
//   a quarter of the largest x extent, along the other axes twice the largest extent there. The
//   cells of one x-row are adjacent in memory, so any run of cells of a row is one contiguous
//   range of boxes, and the thin x cells make that range tight around the box.
// - A counting sort orders the boxes by cell; a gather, prefetching both cache lines a caller's
//   box may straddle, copies them into separate arrays of lower and upper coordinates (and ids)
//   in that order, so that a vector compare tests 8 candidates at once (4 without AVX2)
//   (peers/grid_lanes.hpp, AVX2 where the processor has it), the hits packed without a branch.
// - A box tests the rest of its own row up to the cell of its upper corner, and the later rows
//   (in row order) its window reaches: rows whose lower corners could overlap it, lower corners
//   in [min - largest extent, max] on each axis. Every pair is tested once, from the box whose
//   row comes first, or from the earlier box of a shared row.
// - Boxes far larger than the rest ("oversized": an extent above twice the 95th percentile of a
//   sample) would inflate every cell; they stay out of the cells, each is tested against the rows
//   its window covers, and they are paired among themselves by a nested grid.
// - With two threads, each tests half the boxes and gathers half the arrays.
// - Every buffer is kept between calls.
//
// Exactness rests on monotonicity alone, whatever the cell sides: the cell of a coordinate,
// min(max((v - low) * inverse side, 0), cells - 1) in float and then truncated, never decreases
// as v grows, since each rounded operation is monotone. A box b overlapping a has
// b.min <= a.max, so its cell is at most a.max's; and b.min >= a.min - extent(b) >= a.min - E,
// where E, the largest extent, is rounded up to a float, so fl(a.min - E) <= b.min (b.min is a
// float) and its cell is at most b.min's. The window is therefore never too small; the cell
// counts per axis stay below 2^20, exact in float.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "peers/grid_lanes.hpp"
#include "scenes/scene.hpp"
#include "smb/pair.hpp"

namespace smb::bench {

template <int Dim>
class UniformGrid {
public:
    /// Cell sides as multiples of the largest extent on their axis.
    struct Shape {
        double x_side = 0.25;
        double other_sides = 2.0;
        double cells_per_box = 2.0;  ///< at most; sparse scenes get larger cells
    };
    /// Two boxes at these positions of the grid's order (see order()).
    struct PositionPair {
        std::uint32_t a = 0;
        std::uint32_t b = 0;
    };

    explicit UniformGrid(Shape shape = {}, int threads = 1);

    /// Appends every overlapping pair of `boxes` (box i under ids[i]) to `pairs`, each once, a < b.
    void find_pairs(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids, std::vector<Pair>& pairs);

    /// The same as positions in order(): every overlapping pair once, in any order within it.
    void find_position_pairs(std::span<const BenchBox<Dim>> boxes, std::vector<PositionPair>& pairs);
    /// The input index of the box at each position of the last call: cell order, then the
    /// oversized boxes.
    [[nodiscard]] std::span<const std::uint32_t> order() const noexcept { return order_; }
    /// Appends to `positions` the position of every box of the last call that overlaps `box`.
    void find_overlapping(const BenchBox<Dim>& box, std::vector<std::uint32_t>& positions) const;

    [[nodiscard]] std::size_t cell_count() const noexcept { return cell_total_; }
    [[nodiscard]] double cell_side(int axis) const noexcept { return 1 / static_cast<double>(inverse_side_[axis]); }
    [[nodiscard]] std::size_t oversized_count() const noexcept { return order_.size() - grid_count_; }
    [[nodiscard]] std::size_t lanes() const noexcept { return lanes_; }

private:
    using Index = std::uint32_t;
    static constexpr std::size_t padding = 32;  ///< floats readable past the last box

    /// Where one thread's hits go: by ids (find_pairs) or by positions (find_position_pairs).
    struct IdSink;
    struct PositionSink;

    void arrange(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids);
    void choose_oversize_limits(std::span<const BenchBox<Dim>> boxes);
    void measure(std::span<const BenchBox<Dim>> boxes);
    void lay_out(std::size_t box_count);
    void sort_into_cells(std::span<const BenchBox<Dim>> boxes);
    void gather(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids, std::size_t from, std::size_t to);
    template <class Sink>
    void scan(Sink& sink, std::size_t from, std::size_t to, std::vector<Index>& hits) const;
    template <std::size_t Lanes, class Sink>
    void scan_in_lanes(Sink& sink, std::size_t from, std::size_t to, std::vector<Index>& hits) const;
    template <class Sink>
    [[gnu::target("avx2,popcnt")]] void scan_avx2(Sink& sink, std::size_t from, std::size_t to,
                                                  std::vector<Index>& hits) const;
    template <class Sink>
    void run_threads(std::array<Sink, 2>& sinks);

    [[nodiscard]] bool is_oversized(const BenchBox<Dim>& box) const noexcept {
        bool oversized = false;
        for (int k = 0; k < Dim; ++k) oversized |= box.max[k] - box.min[k] > oversize_limit_[k];
        return oversized;
    }
    /// The cell coordinate of `value` on `axis`, clamped into the grid; monotone in `value`.
    [[nodiscard]] Index cell_of(float value, int axis) const noexcept {
        const float raw = (value - low_[axis]) * inverse_side_[axis];
        return static_cast<Index>(std::min(std::max(raw, 0.0f), last_cell_[axis]));
    }
    [[nodiscard]] std::size_t flat_cell(const std::array<float, Dim>& corner) const noexcept {
        std::size_t flat = 0;
        for (int k = Dim - 1; k >= 0; --k) flat = flat * cells_[k] + cell_of(corner[k], k);
        return flat;
    }
    [[nodiscard]] grid_lanes::Columns<Dim> columns() const noexcept {
        grid_lanes::Columns<Dim> columns;
        for (int k = 0; k < Dim; ++k) {
            columns.min[k] = min_[k].data();
            columns.max[k] = max_[k].data();
        }
        return columns;
    }

    Shape shape_;
    int threads_ = 1;
    std::size_t lanes_ = 4;
    std::array<float, Dim> oversize_limit_{};
    std::array<float, Dim> low_{};
    std::array<double, Dim> range_{};          ///< of the lower corners in the cells
    std::array<float, Dim> largest_extent_{};  ///< of the boxes in the cells, rounded up
    std::array<float, Dim> inverse_side_{};
    std::array<float, Dim> last_cell_{};
    std::array<std::size_t, Dim> cells_{};
    std::size_t cell_total_ = 0;
    std::size_t grid_count_ = 0;  ///< boxes in the cells; the oversized follow them in order_

    std::vector<float> sample_;
    std::vector<Index> cell_of_box_;
    std::vector<Index> cell_begin_;  ///< cell c holds positions [cell_begin_[c], cell_begin_[c + 1])
    std::vector<Index> order_;
    std::array<std::vector<float>, Dim> min_;
    std::array<std::vector<float>, Dim> max_;
    std::vector<BoxId> ids_;  ///< in order, for find_pairs
    std::vector<BenchBox<Dim>> oversized_boxes_;
    std::vector<BoxId> oversized_ids_;
    std::vector<PositionPair> oversized_pairs_;
    std::unique_ptr<UniformGrid> oversized_grid_;
    std::array<std::vector<Index>, 2> hits_;
    std::vector<Pair> second_thread_pairs_;
    std::vector<PositionPair> second_thread_position_pairs_;
};

}  // namespace smb::bench
