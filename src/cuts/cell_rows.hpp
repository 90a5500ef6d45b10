// SPDX-License-Identifier: MIT
#pragma once
// The row tests of a cell laid out in columns (cell_scratch.hpp): each box of the cell, a row,
// against the boxes after it, four or eight at a time (float_lanes.hpp), on the eight lanes of
// AVX2 where the processor has them and on four elsewhere. Two kinds of row: the all-pairs
// test, which writes its hits down, and the sweep on x of a crowded cell, which reports them.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>

#include "cuts/cell_scratch.hpp"
#include "cuts/float_lanes.hpp"
#include "cuts/monotone_key.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <int Dim>
struct CellRows {
    using Mask = typename CellScratch<Dim>::Mask;
    static constexpr std::uint32_t kAllInside = (1U << Dim) - 1;

    // The cell's boxes, one array per coordinate (as floats), in x order for the sweep or as
    // registered for the all-pairs test, padded with boxes that reach nothing (min NaN, key above
    // every real key) so that the last group of lanes may read past the end; and the pairs the
    // lanes passed, as (i << 16 | j), in row order.
    typename CellScratch<Dim>::Columns columns;

    // The sweep on x: box i against the boxes after it whose key does not pass the key of its
    // max x, a group of lanes at a time. Keys never decrease along the order, so once a group
    // starts past that key no later box reaches i on x; within a group, min_j <= max_i drops
    // the others. A box j that reaches i has min_j <= max_i, so key_j <= key(to_float(max_i)):
    // the scan goes far enough. The other end, max_j >= min_i, needs no test: with float boxes
    // equal keys are equal values, so min_i <= min_j <= max_j; with double boxes a disorder
    // hidden by equal keys can pass the float test, which the exact test then settles.
    // Reports report(position_i, position_j) for every pair that the lanes and, for double
    // boxes, the exact test pass; the cell is laid out in x order, its keys written.
    template <class Real, class Report>
    void sweep(std::size_t m, std::span<const Box<Real, Dim>> boxes, Report& report) const {
#if SMB_LANES_AVX2
        if (cpu_has_avx2()) {
            sweep_avx2(m, boxes, report);
            return;
        }
#endif
        sweep_in_lanes<4>(m, boxes, report);
    }

    /// The sweep of sweep() for float boxes, whose lanes' test is exact: the hits of each group
    /// of lanes are written down without a branch (i << 16 | j, as pair_rows() writes them; the
    /// cell holds at most 2^15 boxes), and flush(hits, count) takes them, in row order, whenever
    /// fewer places are left than one turn may write, and at the end. A branch on each hit
    /// guessed wrong for most rows. `long_rows`: most rows reach past one group of lanes
    /// (CellXOrder::reach()), and the sweep reads two groups a turn.
    template <class Flush>
    void swept_rows(std::size_t m, std::size_t room, bool long_rows, Flush&& flush) {
#if SMB_LANES_AVX2
        if (cpu_has_avx2()) {
            if (long_rows)
                swept_rows_avx2<2>(m, room, flush);
            else
                swept_rows_avx2<1>(m, room, flush);
            return;
        }
#endif
        if (long_rows)
            swept_rows_in_lanes<4, 2>(m, room, flush);
        else
            swept_rows_in_lanes<4, 1>(m, room, flush);
    }

    /// A box from outside the cell (an oversized box that covers it: its `own` inside bits, its
    /// `low` and `high` corners, as floats) against the laid-out boxes from `from` on: every one
    /// (`sorted` false), or, the cell laid out in x order, those whose min x does not pass
    /// high[0]. The local numbers of those that pass the lanes' test (both ways on every axis,
    /// and the lower-corner rule) are written down without a branch and handed to
    /// flush(hits, count) whenever fewer than `room` - Lanes places are left, and at the end.
    template <class Flush>
    void visitor_row(std::size_t from, std::size_t m, bool sorted, Mask own, const std::array<float, Dim>& low,
                     const std::array<float, Dim>& high, std::size_t room, Flush&& flush) const {
#if SMB_LANES_AVX2
        if (cpu_has_avx2()) {
            visitor_row_avx2(from, m, sorted, own, low, high, room, flush);
            return;
        }
#endif
        visitor_row_in_lanes<4>(from, m, sorted, own, low, high, room, flush);
    }

    /// Writes the hit list with every pair (i << 16 | j, i < j) that passes the lanes' test on
    /// every axis both ways; returns their number.
    std::size_t pair_rows(std::size_t m) {
#if SMB_LANES_AVX2
        if (cpu_has_avx2()) return pair_rows_avx2(m);
#endif
        return pair_rows_in_lanes<4>(m);
    }

private:
    // Through memcpy: the arrays are not aligned to the lanes' width.
    template <class Lanes, class Value>
    static void load(Lanes& lanes, const Value* from) noexcept {
        std::memcpy(&lanes, from, sizeof lanes);
    }

    /// One bit for each of the candidates j..j+Lanes-1 that box i (its `own` inside bits, its
    /// `low` and `high` corners) may report: tested both ways on every axis, except the lower
    /// end on x when swept.
    template <std::size_t Lanes, bool Swept>
    [[gnu::always_inline]] inline unsigned lanes_hit(std::size_t j, Mask own, const std::array<float, Dim>& low,
                                                     const std::array<float, Dim>& high) const {
        using FloatVector = typename FloatLanes<Lanes>::Floats;
        using MaskLanes = typename FloatLanes<Lanes>::Masks;
        MaskLanes others;
        load(others, columns.inside + j);
        MaskLanes hit = (others | own) == static_cast<Mask>(kAllInside);
        for (int k = 0; k < Dim; ++k) {
            FloatVector lower;
            load(lower, columns.min[k] + j);
            hit &= lower <= high[k];
            if (!Swept || k > 0) {
                FloatVector upper;
                load(upper, columns.max[k] + j);
                hit &= upper >= low[k];
            }
        }
        return lane_bits<Lanes>(hit);
    }

    /// The corners of row i's box, tested against every group of candidates of its row.
    [[gnu::always_inline]] inline void row_corners(std::size_t i, std::array<float, Dim>& low,
                                                   std::array<float, Dim>& high) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            low[k] = columns.min[k][i];
            high[k] = columns.max[k][i];
        }
    }

    template <std::size_t Lanes, class Real, class Report>
    [[gnu::always_inline]] inline void sweep_in_lanes(std::size_t m, std::span<const Box<Real, Dim>> boxes,
                                                      Report& report) const {
        const std::uint32_t* key = columns.key;
        const Mask* inside = columns.inside;
        const std::uint32_t* position = columns.position;
        for (std::size_t i = 0; i < m; ++i) {
            const std::uint32_t stop = monotone_key(columns.max[0][i]);
            std::array<float, Dim> low{}, high{};  // low[0] unused, see sweep()
            row_corners(i, low, high);
            for (std::size_t j = i + 1; key[j] <= stop; j += Lanes) {
                unsigned bits = lanes_hit<Lanes, true>(j, inside[i], low, high);
                while (bits != 0) {
                    const std::uint32_t other = position[j + static_cast<std::size_t>(std::countr_zero(bits))];
                    bits &= bits - 1;
                    if (std::is_same_v<Real, float> || overlaps(boxes[position[i]], boxes[other]))
                        report(position[i], other);
                }
            }
        }
    }

    /// Writes the hit list with every pair (i << 16 | j, i < j) that passes the lanes' test, row by
    /// row; returns their number.
    template <std::size_t Lanes>
    [[gnu::always_inline]] inline std::size_t pair_rows_in_lanes(std::size_t m) {
        using MaskLanes = typename FloatLanes<Lanes>::Masks;
        MaskLanes lane{};
        for (std::size_t l = 0; l < Lanes; ++l) lane[l] = static_cast<Mask>(l);
        std::uint32_t* const first = columns.hits;
        std::uint32_t* out = first;
        for (std::size_t i = 0; i < m; ++i) {
            std::array<float, Dim> low{}, high{};
            row_corners(i, low, high);
            const Mask own = columns.inside[i];
            MaskLanes pair = lane + static_cast<Mask>((i << 16) | (i + 1));
            for (std::size_t j = i + 1; j < m; j += Lanes) {
                out = append_set_lanes<Lanes>(out, lanes_hit<Lanes, false>(j, own, low, high), pair);
                pair += static_cast<Mask>(Lanes);
            }
        }
        return static_cast<std::size_t>(out - first);
    }

    template <std::size_t Lanes, std::size_t Groups, class Flush>
    [[gnu::always_inline]] inline void swept_rows_in_lanes(std::size_t m, std::size_t room, Flush& flush) {
        using MaskLanes = typename FloatLanes<Lanes>::Masks;
        MaskLanes lane{};
        for (std::size_t l = 0; l < Lanes; ++l) lane[l] = static_cast<Mask>(l);
        const std::uint32_t* key = columns.key;
        const Mask* inside = columns.inside;
        std::uint32_t* const first = columns.hits;
        std::uint32_t* const full = first + (room - Groups * Lanes);
        std::uint32_t* out = first;
        for (std::size_t i = 0; i < m; ++i) {
            const std::uint32_t stop = monotone_key(columns.max[0][i]);
            std::array<float, Dim> low{}, high{};  // low[0] unused, see sweep()
            row_corners(i, low, high);
            MaskLanes pair = lane + static_cast<Mask>((i << 16) | (i + 1));
            // Groups of lanes a turn: where rows reach about ten boxes along x, two a turn end
            // most rows after one, where one a turn ended them after one, two or three and was
            // guessed wrong about once a row. The lanes test x too, so the candidates of a turn
            // past `stop` report nothing.
            for (std::size_t j = i + 1; key[j] <= stop; j += Groups * Lanes) {
                if (out > full) {
                    flush(static_cast<const std::uint32_t*>(first), static_cast<std::size_t>(out - first));
                    out = first;
                }
                for (std::size_t group = 0; group < Groups; ++group) {
                    out = append_set_lanes<Lanes>(out, lanes_hit<Lanes, true>(j + group * Lanes, inside[i], low, high),
                                                  pair);
                    pair += static_cast<Mask>(Lanes);
                }
            }
        }
        flush(static_cast<const std::uint32_t*>(first), static_cast<std::size_t>(out - first));
    }

    template <std::size_t Lanes, class Flush>
    [[gnu::always_inline]] inline void visitor_row_in_lanes(std::size_t from, std::size_t m, bool sorted, Mask own,
                                                            const std::array<float, Dim>& low,
                                                            const std::array<float, Dim>& high, std::size_t room,
                                                            Flush& flush) const {
        using MaskLanes = typename FloatLanes<Lanes>::Masks;
        MaskLanes lane{};
        for (std::size_t l = 0; l < Lanes; ++l) lane[l] = static_cast<Mask>(l);
        std::uint32_t* const first = columns.hits;
        std::uint32_t* const full = first + (room - Lanes);
        std::uint32_t* out = first;
        const float stop = sorted ? high[0] : std::numeric_limits<float>::infinity();
        // The lanes past m hold the padding, which no test passes.
        for (std::size_t j = from; j < m && !(columns.min[0][j] > stop); j += Lanes) {
            if (out > full) {
                flush(static_cast<const std::uint32_t*>(first), static_cast<std::size_t>(out - first));
                out = first;
            }
            out = append_set_lanes<Lanes>(out, lanes_hit<Lanes, false>(j, own, low, high), lane + static_cast<Mask>(j));
        }
        flush(static_cast<const std::uint32_t*>(first), static_cast<std::size_t>(out - first));
    }

#if SMB_LANES_AVX2
    template <class Flush>
    [[gnu::target("avx2,popcnt")]] void visitor_row_avx2(std::size_t from, std::size_t m, bool sorted, Mask own,
                                                         const std::array<float, Dim>& low,
                                                         const std::array<float, Dim>& high, std::size_t room,
                                                         Flush& flush) const {
        visitor_row_in_lanes<8>(from, m, sorted, own, low, high, room, flush);
    }
    template <std::size_t Groups, class Flush>
    [[gnu::target("avx2,popcnt")]] void swept_rows_avx2(std::size_t m, std::size_t room, Flush& flush) {
        swept_rows_in_lanes<8, Groups>(m, room, flush);
    }
    template <class Real, class Report>
    [[gnu::target("avx2")]] void sweep_avx2(std::size_t m, std::span<const Box<Real, Dim>> boxes,
                                            Report& report) const {
        sweep_in_lanes<8>(m, boxes, report);
    }
    [[gnu::target("avx2,popcnt")]] std::size_t pair_rows_avx2(std::size_t m) { return pair_rows_in_lanes<8>(m); }
#endif
};

}  // namespace smb::detail
