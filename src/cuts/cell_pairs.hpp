// SPDX-License-Identifier: MIT
#pragma once
// The cell check of the persistent-cut pipeline: the pairs of one cell, found in one of two ways
// by the number m of boxes registered in it. Either way the boxes are copied out one float array
// per coordinate (cell_scratch.hpp), read eight candidates at a time (cell_rows.hpp), and the
// hits written down without a branch (a compress through a permutation table), reported after.
//
// - Up to kAllPairsLimit boxes, in cells cut on every axis (about 46 registered in 3D): every
//   pair is tested, as registered. No keys, no sort, and loops whose lengths do not depend on the
//   boxes' sizes, as a sweep's scan does, at one mispredicted exit per box.
// - Beyond, and in every column (x left uncut, level_regrouping.hpp): the boxes get local numbers
//   (the paper's global-local map), are sorted on x (cell_x_order.hpp) and swept on x with direct
//   tests on the other axes. A long column swept on x tests about as many candidates per box as
//   boxes reach it along x, where a cube of the same population tests every box of the cube.
//
// A pair shared by several cells is reported only by the cell that holds the lower corner of the
// two boxes' intersection, p[k] = max(a.min[k], b.min[k]). This replaces the paper's mask array:
// it needs no per-box state, and it stays exact whatever the number of cells a box touches.
// Every box registered in a cell has min[k] < the cell's upper plane on every axis (its min lies
// in the cell's segment or before it), so p lies in the cell iff, on every axis, a.min[k] or
// b.min[k] is at or above the cell's lower plane: one bit per axis and box, computed once.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "core/assert.hpp"
#include "core/bulk_vector.hpp"
#include "core/tuning.hpp"
#include "cuts/cell_floor.hpp"
#include "cuts/cell_rows.hpp"
#include "cuts/cell_scratch.hpp"
#include "cuts/cell_x_order.hpp"
#include "cuts/monotone_key.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class CellPairs {
public:
    static constexpr std::uint32_t kAllInside = CellRows<Dim>::kAllInside;

    /// Cells of up to this many registered boxes are checked by testing every pair.
    static constexpr std::size_t kAllPairsLimit = tuning::all_pairs_limit;
    /// check_all_pairs() packs local numbers as i << 16 | j in the lanes' signed 32-bit
    /// integers: it takes cells of up to this many boxes (the pipeline's, up to kAllPairsLimit).
    static constexpr std::size_t kMostPaired = std::size_t{1} << 15;

    /// Reports every pair of `entries` (positions of the boxes registered in the cell) whose
    /// lower intersection corner lies in the cell, and appends to `home` the positions whose own
    /// lower corner does: the order the next detection starts from. Returns the insertion-sort
    /// moves (none when every pair is tested).
    template <class Report, class Id>
    std::size_t check(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                      std::span<const Id> ids, const CellFloor<Real, Dim>& floor, Report& report,
                      BulkVector<std::uint32_t>& home) {
        if (entries.size() <= kAllPairsLimit) {
            check_all_pairs(entries, boxes, floor, report, home);
            return 0;
        }
        return check_by_sweep(entries, boxes, ids, floor, report, home);
    }

    /// Held boxes that overlap by at least `margin` on every axis (held_sure_margin()) hold
    /// input boxes that overlap: the all-pairs test then calls report(a, b, true) where the
    /// report takes a third argument, and report(a, b, false) for the other pairs it passes,
    /// which the caller tests again. The default, infinity, proves nothing.
    void set_sure_margin(float margin) noexcept { sure_margin_ = margin; }

    /// check() by testing every pair; `home` gets the positions in the order of `entries`.
    template <class Report>
    void check_all_pairs(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                         const CellFloor<Real, Dim>& floor, Report& report, BulkVector<std::uint32_t>& home) {
        lay_out(entries, boxes, floor);
        laid_out_swept_ = false;
        test_all_pairs(entries.size(), boxes, report, home);
    }

    /// check() by a sort and a sweep on x; `home` gets the positions in x order (ties by
    /// coordinate and id). Returns the insertion-sort moves.
    template <class Report, class Id>
    std::size_t check_by_sweep(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                               std::span<const Id> ids, const CellFloor<Real, Dim>& floor, Report& report,
                               BulkVector<std::uint32_t>& home) {
        const std::size_t m = entries.size();
        const std::size_t moves = x_order_.sort(entries, boxes);
        laid_out_swept_ = true;
        x_order_.order_equal_keys(entries, boxes, ids);
        lay_out_sorted(x_order_.keys(), m, entries, boxes, floor);
        long_rows_ = kExactLanes && m <= kMostPaired && x_order_.reach() >= tuning::long_sweep_rows;
        if constexpr (kExactLanes) {
            if (m <= kMostPaired) {
                rows_.swept_rows(m, kSweptHitRoom, long_rows_, [&](const std::uint32_t* hits, std::size_t count) {
                    report_hits(hits, count, boxes, report);
                });
                append_home(m, home);
                return moves;
            }
        }
        rows_.sweep(m, boxes, report);
        append_home(m, home);
        return moves;
    }

    /// After check() or check_by_sweep() of a cell: the oversized boxes that cover it (positions
    /// `visitors`, the cell's lower planes `floor`) against the cell's boxes, each pair whose
    /// lower intersection corner lies in the cell reported as report(visitor, position). A swept
    /// cell is laid out in x order, so each visitor reads only the boxes that reach its x range
    /// (within widest_x() before its min x, up to its max x).
    template <class Report>
    void check_visitors(std::span<const std::uint32_t> visitors, std::span<const Box<Real, Dim>> boxes,
                        const CellFloor<Real, Dim>& floor, Report& report) const {
        const bool swept = laid_out_swept_;
        const std::size_t m = laid_out_;
        const float* min_x = rows_.columns.min[0];
        const std::uint32_t* position = rows_.columns.position;
        for (const std::uint32_t visitor : visitors) {
            const Box<Real, Dim>& box = boxes[visitor];
            std::array<float, Dim> low{}, high{};
            Mask own = 0;
            for (int k = 0; k < Dim; ++k) {
                low[k] = to_float(box.min[k]);
                high[k] = to_float(box.max[k]);
                own |= static_cast<Mask>((box.min[k] >= floor[k] ? 1U : 0U) << k);
            }
            std::size_t from = 0;
            if (swept) {
                // A box that reaches the visitor's min x has min x >= that min x - widest_x();
                // rounded down, and rounding to floats keeps the order, so none is skipped.
                const float reach_from =
                    to_float(std::nextafter(box.min[0] - widest_x(), -std::numeric_limits<Real>::infinity()));
                from = static_cast<std::size_t>(
                    std::partition_point(min_x, min_x + m, [&](float x) { return x < reach_from; }) - min_x);
            }
            rows_.visitor_row(from, m, swept, own, low, high, hit_room_,
                              [&](const std::uint32_t* hits, std::size_t count) {
                                  for (std::size_t t = 0; t < count; ++t) {
                                      const std::uint32_t other = position[hits[t]];
                                      if (kExactLanes || overlaps(box, boxes[other])) report(visitor, other);
                                  }
                              });
        }
    }

    /// After check_by_sweep(): the cell's positions in x order and a bound on its boxes' x
    /// extent (CellXOrder::widest_x()); valid until the next check.
    [[nodiscard]] std::span<const std::uint32_t> swept_positions() const noexcept {
        return {rows_.columns.position, x_order_.size()};
    }
    [[nodiscard]] Real widest_x() const noexcept { return x_order_.widest_x(); }
    /// Whether the last sweep of float boxes read two groups of lanes a turn (tuning::long_sweep_rows).
    [[nodiscard]] bool swept_long_rows() const noexcept { return long_rows_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return x_order_.bytes_held() + scratch_.bytes_held() + own_home_.capacity() * sizeof(std::uint32_t);
    }

private:
    // Four or eight candidates are tested at once (GCC vector extensions; FloatLanes), always on
    // floats. Double boxes are laid out rounded to floats (to_float), which keeps every order,
    // so the float test passes every pair that overlaps, and each pair it passes is tested
    // again exactly. Four double lanes fill two SSE registers and are slower than one candidate
    // at a time (and the layout takes twice the bytes); four float lanes fill one.
    static constexpr std::size_t kPadding = 16;  // the most lanes a turn of a row reads past its last box

    static constexpr bool kExactLanes = std::is_same_v<Real, float>;
    using Mask = typename CellScratch<Dim>::Mask;

    /// The hits a sweep writes down before it hands them on (CellRows::swept_rows()).
    static constexpr std::size_t kSweptHitRoom = 2048;

    void lay_out_sorted(const std::uint64_t* order, std::size_t m, std::span<const std::uint32_t> entries,
                        std::span<const Box<Real, Dim>> boxes, const CellFloor<Real, Dim>& floor) {
        lay_out_columns(
            m, kSweptHitRoom, [&](std::size_t r) { return entries[order[r] & 0xFFFFFFFFU]; },
            [&](std::size_t r) { return static_cast<std::uint32_t>(order[r] >> 32); }, boxes, floor);
    }

    /// As registered, for the all-pairs test, which reads no keys, with room for every pair.
    void lay_out(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                 const CellFloor<Real, Dim>& floor) {
        const std::size_t m = entries.size();
        lay_out_columns(
            m, m * (m - (m > 0 ? 1 : 0)) / 2 + kPadding, [&](std::size_t r) { return entries[r]; }, NoKeys{}, boxes,
            floor);
    }

    struct NoKeys {};  // the all-pairs test reads no keys: none are written

    template <class PositionAt, class KeyAt>
    [[gnu::always_inline]] inline void lay_out_columns(std::size_t m, std::size_t hit_room, PositionAt position_at,
                                                       KeyAt key_at, std::span<const Box<Real, Dim>> boxes,
                                                       const CellFloor<Real, Dim>& floor) {
        const std::size_t padded = m + kPadding;
        rows_.columns = scratch_.lay_out_for(padded, hit_room);
        laid_out_ = m;
        hit_room_ = hit_room;
        for (std::size_t r = 0; r < m; ++r) {
            const std::uint32_t position = position_at(r);
            const Box<Real, Dim>& box = boxes[position];
            std::uint32_t inside = 0;
            for (int k = 0; k < Dim; ++k) {
                rows_.columns.min[k][r] = to_float(box.min[k]);
                rows_.columns.max[k][r] = to_float(box.max[k]);
                inside |= (box.min[k] >= floor[k] ? 1U : 0U) << k;
            }
            rows_.columns.inside[r] = static_cast<Mask>(inside);
            if constexpr (!std::is_same_v<KeyAt, NoKeys>) rows_.columns.key[r] = key_at(r);
            rows_.columns.position[r] = position;
        }
        for (std::size_t r = m; r < padded; ++r) {
            for (int k = 0; k < Dim; ++k) {
                // NaN: no comparison with it holds, whatever the box it is tested against.
                rows_.columns.min[k][r] = std::numeric_limits<float>::quiet_NaN();
                rows_.columns.max[k][r] = -std::numeric_limits<float>::infinity();
            }
            rows_.columns.inside[r] = 0;
            rows_.columns.key[r] = ~std::uint32_t{0};  // above the key of any finite max
            rows_.columns.position[r] = 0;
        }
    }

    // Every box i against every box after it, a group of lanes at a time, on all axes both ways
    // (no order to lean on); the lanes past m hold the padding, which no test passes. The rows
    // only write the hits down, without a branch (append_set_lanes); the report follows. A
    // branch on each group's hits mispredicted about once a group in four.
    template <class Report>
    void test_all_pairs(std::size_t m, std::span<const Box<Real, Dim>> boxes, Report& report,
                        BulkVector<std::uint32_t>& home) {
        SMB_ASSERT(m <= kMostPaired, "a cell tested pair by pair packs two local numbers in 31 bits");
        report_hits(rows_.columns.hits, rows_.pair_rows(m), boxes, report);
        append_home(m, home);
    }

    // Reports the pairs of a hit list (i << 16 | j, local numbers of the layout).
    template <class Report>
    void report_hits(const std::uint32_t* hits, std::size_t count, std::span<const Box<Real, Dim>> boxes,
                     Report& report) const {
        const std::uint32_t* position = rows_.columns.position;
        for (std::size_t t = 0; t < count; ++t) {
            const std::uint32_t i = hits[t] >> 16;
            const std::uint32_t j = hits[t] & 0xFFFFU;
            if constexpr (kExactLanes && std::invocable<Report&, std::uint32_t, std::uint32_t, bool>) {
                // Exact input (an infinite margin) has nothing to settle: the test is skipped.
                report(position[i], position[j], settles() && overlap_by_margin(i, j));
            } else if (kExactLanes || overlaps(boxes[position[i]], boxes[position[j]])) {
                report(position[i], position[j]);
            }
        }
    }

    /// Whether the margin can settle anything: exact input has an infinite one.
    [[nodiscard]] bool settles() const noexcept { return sure_margin_ != std::numeric_limits<float>::infinity(); }

    // Whether laid-out boxes i and j overlap by at least the sure margin on every axis, read
    // from the columns the rows just read (in L1), without a branch.
    [[nodiscard]] bool overlap_by_margin(std::uint32_t i, std::uint32_t j) const noexcept {
        bool by_margin = true;
        for (int k = 0; k < Dim; ++k) {
            const float* min = rows_.columns.min[k];
            const float* max = rows_.columns.max[k];
            by_margin &= (max[j] - min[i] >= sure_margin_) & (max[i] - min[j] >= sure_margin_);
        }
        return by_margin;
    }

    // Every box whose lower corner lies in the cell, in the order of the layout (x order when
    // swept, as registered for the pair test); a branch here would guess wrong for one box in
    // four. Gathered apart first: growing `home` by m and back would make it outgrow the
    // capacity reserved for it, at the last cells.
    void append_home(std::size_t m, BulkVector<std::uint32_t>& home) {
        if (own_home_.size() < m) own_home_.resize(m);
        std::uint32_t* out = own_home_.data();
        for (std::size_t r = 0; r < m; ++r) {
            *out = rows_.columns.position[r];
            out += rows_.columns.inside[r] == static_cast<Mask>(kAllInside) ? 1 : 0;
        }
        home.insert(home.end(), own_home_.data(), out);
    }

    CellXOrder<Real, Dim> x_order_;  // the keys of a swept cell, in x order
    CellScratch<Dim> scratch_;
    CellRows<Dim> rows_;  // the columns laid out in scratch_, and the row tests that read them
    float sure_margin_ = std::numeric_limits<float>::infinity();
    std::vector<std::uint32_t> own_home_;  // the cell's home boxes, on their way to `home`
    std::size_t laid_out_ = 0;             // boxes of the cell laid out last
    std::size_t hit_room_ = 0;             // and the room for hits after them
    bool laid_out_swept_ = false;          // and whether it was laid out in x order
    bool long_rows_ = false;               // see swept_long_rows()
};

}  // namespace smb::detail
