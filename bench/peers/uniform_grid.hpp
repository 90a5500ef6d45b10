// SPDX-License-Identifier: MIT
#pragma once
// The uniform grid of the comparison, rebuilt from scratch on every call and written to be as fast
// as a single-threaded grid gets on boxes of similar size:
//
// - Cell side = the largest box extent on that axis (a hair more), so two overlapping boxes have
//   their lower corners in the same or in neighbouring cells. Each box is stored once, in the cell
//   of its lower corner, and a cell is tested against itself and against its 13 (3D) or 4 (2D)
//   neighbours of the "upper half", so every candidate pair is tested exactly once and no pair
//   needs deduplication.
// - The cells form a dense array (no hashing), padded by one empty cell on every side so that
//   neighbour lookups need no bounds checks. A counting sort places the boxes, copied with their
//   ids into 32-byte (3D) records, in cell order: cells along x are adjacent in memory, so each
//   neighbour row (x-1, x, x+1) is one contiguous range, and a cell plus its x+1 neighbour too.
// - A box skips the upper neighbours its upper corner does not reach (about 40% of the tests),
//   and tests a record with one SSE comparison (records hold min and -max).
// - Boxes far larger than the rest ("oversized": an extent above twice the 95th percentile of a
//   sample) would inflate every cell; they stay out of the grid, each is tested against the
//   cells its lower-corner window covers, and they are paired among themselves by a nested grid.
// - Every buffer is kept between calls.
//
// Exactness: the cell coordinate floor((v - low) / side), computed in double, is monotone in v,
// and the side exceeds the largest extent by a relative 1e-6, far above the rounding error, so
// the lower corners of two overlapping boxes lie at most one cell apart on every axis.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "scenes/scene.hpp"
#include "smb/pair.hpp"

namespace smb::bench {

template <int Dim>
class UniformGrid {
public:
    /// Appends every overlapping pair of `boxes` (box i under ids[i]) to `pairs`, each once.
    void find_pairs(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids, std::vector<Pair>& pairs);

    [[nodiscard]] std::size_t cell_count() const noexcept { return cell_total_; }
    [[nodiscard]] double cell_side(int axis) const noexcept { return 1 / inverse_side_[axis]; }
    [[nodiscard]] std::size_t oversized_count() const noexcept { return oversized_ids_.size(); }

private:
    /// A box in cell order: what the pair tests read, in one record. The upper corner is stored
    /// negated, so that the closed overlap test is one "lower or equal" on all 2 * Dim lanes:
    /// b.min <= a.max and -b.max <= -a.min (negation is exact).
    struct Record {
        std::array<float, 2 * Dim> lanes;  ///< min, then -max
        BoxId id;
    };
    /// What a box tests records against: its max, then -min.
    struct Query {
        std::array<float, 2 * Dim> lanes;
    };
    using Index = std::uint32_t;
    static constexpr Index not_in_grid = std::numeric_limits<Index>::max();

    void brute_force(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids, std::vector<Pair>& pairs) const;
    void choose_oversize_limits(std::span<const BenchBox<Dim>> boxes);
    void measure(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids);
    void lay_out(std::size_t box_count);
    void sort_into_cells(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids);
    void pairs_in_cells(std::vector<Pair>& pairs) const;
    void oversized_against_cells(std::vector<Pair>& pairs) const;

    [[nodiscard]] bool is_oversized(const BenchBox<Dim>& box) const noexcept {
        bool oversized = false;
        for (int k = 0; k < Dim; ++k) oversized |= box.max[k] - box.min[k] > oversize_limit_[k];
        return oversized;
    }
    /// Clamped into the grid; monotone in `value`.
    [[nodiscard]] std::int64_t cell_coordinate(double value, int axis) const noexcept {
        const double raw = std::floor((value - low_[axis]) * inverse_side_[axis]);
        return static_cast<std::int64_t>(std::clamp(raw, 0.0, static_cast<double>(cells_[axis] - 1)));
    }
    /// The same for a value no lower than the grid's lowest lower corner, such as any coordinate
    /// of a box in the grid: truncation is the floor there, and far cheaper.
    [[nodiscard]] std::int64_t lower_corner_coordinate(float value, int axis) const noexcept {
        const auto raw = static_cast<std::int64_t>((static_cast<double>(value) - low_[axis]) * inverse_side_[axis]);
        return std::min(raw, cells_[axis] - 1);
    }
    /// Flat index in the padded array of the cell holding the lower corner of a box in the grid.
    [[nodiscard]] Index flat_cell(const std::array<float, Dim>& corner) const noexcept {
        std::int64_t index = 0;
        for (int k = 0; k < Dim; ++k) index += (lower_corner_coordinate(corner[k], k) + 1) * stride_[k];
        return static_cast<Index>(index);
    }

    static Query query_of(const std::array<float, Dim>& min, const std::array<float, Dim>& max) noexcept {
        Query query;
        for (int k = 0; k < Dim; ++k) {
            query.lanes[k] = max[k];
            query.lanes[Dim + k] = -min[k];
        }
        return query;
    }
    static Query query_of(const Record& record) noexcept {
        Query query;
        for (int k = 0; k < Dim; ++k) {
            query.lanes[k] = -record.lanes[Dim + k];
            query.lanes[Dim + k] = -record.lanes[k];
        }
        return query;
    }
    static Record record_of(const BenchBox<Dim>& box, BoxId id) noexcept {
        Record record;
        for (int k = 0; k < Dim; ++k) {
            record.lanes[k] = box.min[k];
            record.lanes[Dim + k] = -box.max[k];
        }
        record.id = id;
        return record;
    }

    static bool overlap(const Query& query, const Record& record) noexcept {
#if defined(__SSE2__)
        if constexpr (Dim == 3) {
            const __m128 low = _mm_cmple_ps(_mm_loadu_ps(record.lanes.data()), _mm_loadu_ps(query.lanes.data()));
            // The last two lanes: 64-bit loads (__m128i may alias anything).
            const __m128 high =
                _mm_cmple_ps(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&record.lanes[4]))),
                             _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&query.lanes[4]))));
            return ((_mm_movemask_ps(low) | (_mm_movemask_ps(high) << 4)) & 0x3F) == 0x3F;
        } else {
            return _mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(record.lanes.data()), _mm_loadu_ps(query.lanes.data()))) ==
                   0xF;
        }
#else
        bool result = true;
        for (int k = 0; k < 2 * Dim; ++k) result &= record.lanes[k] <= query.lanes[k];
        return result;
#endif
    }

    std::array<float, Dim> oversize_limit_{};
    std::array<double, Dim> low_{};
    std::array<double, Dim> high_{};
    std::array<double, Dim> largest_extent_{};  ///< of the boxes in the grid
    std::array<double, Dim> inverse_side_{};
    std::array<std::int64_t, Dim> cells_{};   ///< per axis, without the padding
    std::array<std::int64_t, Dim> stride_{};  ///< of the padded array
    std::size_t cell_total_ = 0;              ///< padded

    std::vector<float> sample_;
    std::vector<Index> cell_of_box_;
    std::vector<Index> cell_begin_;  ///< cell c holds records [cell_begin_[c], cell_begin_[c + 1])
    std::vector<Record> records_;
    std::vector<BenchBox<Dim>> oversized_boxes_;
    std::vector<BoxId> oversized_ids_;
    std::unique_ptr<UniformGrid> oversized_grid_;
};

}  // namespace smb::bench
