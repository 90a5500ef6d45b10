// SPDX-License-Identifier: MIT
#include "peers/uniform_grid.hpp"

#include "peers/peer.hpp"

namespace smb::bench {
namespace {

// Below this many boxes testing every pair is faster than laying out a grid.
constexpr std::size_t brute_force_below = 64;
// A box is oversized when an extent exceeds this multiple of that axis's 95th percentile.
constexpr double oversize_factor = 2.0;
constexpr double oversize_quantile = 0.95;
constexpr std::size_t sample_size = 1024;
// The cell side exceeds the largest extent by this relative margin (see the header: exactness).
constexpr double side_margin = 1e-6;
// The dense array may hold at most this many cells per box (sparse scenes get larger cells).
constexpr double cells_per_box_limit = 2.0;

}  // namespace

template <int Dim>
void UniformGrid<Dim>::find_pairs(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids,
                                  std::vector<Pair>& pairs) {
    oversized_boxes_.clear();
    oversized_ids_.clear();
    if (boxes.size() < brute_force_below) {
        brute_force(boxes, ids, pairs);
        return;
    }
    choose_oversize_limits(boxes);
    measure(boxes, ids);
    if (oversized_ids_.size() > boxes.size() / 2) {
        // The sample misjudged the sizes: no box is oversized then.
        oversize_limit_.fill(std::numeric_limits<float>::infinity());
        oversized_boxes_.clear();
        oversized_ids_.clear();
        measure(boxes, ids);
    }
    lay_out(boxes.size() - oversized_ids_.size());
    sort_into_cells(boxes, ids);
    pairs_in_cells(pairs);
    if (oversized_ids_.empty()) return;
    oversized_against_cells(pairs);
    if (!oversized_grid_) oversized_grid_ = std::make_unique<UniformGrid>();
    oversized_grid_->find_pairs(oversized_boxes_, oversized_ids_, pairs);
}

template <int Dim>
void UniformGrid<Dim>::brute_force(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids,
                                   std::vector<Pair>& pairs) const {
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
            if (overlaps(boxes[i], boxes[j])) pairs.push_back(ordered_pair(ids[i], ids[j]));
}

// From an evenly spaced sample: cheap, and only a matter of speed, since oversized boxes are
// handled exactly whatever the limit.
template <int Dim>
void UniformGrid<Dim>::choose_oversize_limits(std::span<const BenchBox<Dim>> boxes) {
    const std::size_t stride = std::max<std::size_t>(1, boxes.size() / sample_size);
    for (int k = 0; k < Dim; ++k) {
        sample_.clear();
        for (std::size_t i = 0; i < boxes.size(); i += stride) sample_.push_back(boxes[i].max[k] - boxes[i].min[k]);
        const auto rank = static_cast<std::ptrdiff_t>(oversize_quantile * static_cast<double>(sample_.size() - 1));
        std::nth_element(sample_.begin(), sample_.begin() + rank, sample_.end());
        oversize_limit_[k] = static_cast<float>(oversize_factor * sample_[static_cast<std::size_t>(rank)]);
    }
}

// The range of the grid boxes' lower corners and their largest extents; oversized boxes set aside.
template <int Dim>
void UniformGrid<Dim>::measure(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids) {
    low_.fill(std::numeric_limits<double>::infinity());
    high_.fill(-std::numeric_limits<double>::infinity());
    std::array<float, Dim> low{}, high{};
    low.fill(std::numeric_limits<float>::infinity());
    high.fill(-std::numeric_limits<float>::infinity());
    std::array<double, Dim> largest{};
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const BenchBox<Dim>& box = boxes[i];
        if (is_oversized(box)) {
            oversized_boxes_.push_back(box);
            oversized_ids_.push_back(ids[i]);
            continue;
        }
        for (int k = 0; k < Dim; ++k) {
            low[k] = std::min(low[k], box.min[k]);
            high[k] = std::max(high[k], box.min[k]);
            // In double: the difference of two floats of similar size is exact there.
            largest[k] = std::max(largest[k], static_cast<double>(box.max[k]) - static_cast<double>(box.min[k]));
        }
    }
    for (int k = 0; k < Dim; ++k) {
        low_[k] = low[k];
        high_[k] = high[k];
        // Guards the last-bit rounding of that difference where it was not exact.
        largest_extent_[k] = largest[k] * (1 + 1e-9);
    }
}

template <int Dim>
void UniformGrid<Dim>::lay_out(std::size_t box_count) {
    std::array<double, Dim> side{};
    for (int k = 0; k < Dim; ++k) {
        const double range = std::max(high_[k] - low_[k], 0.0);
        // A positive side even for flat boxes: about 2^20 cells at most along the range.
        side[k] = std::max({largest_extent_[k] * (1 + side_margin), range * 0x1p-20, 1e-30});
    }
    const double cell_limit = cells_per_box_limit * static_cast<double>(box_count) + 64;
    for (;;) {
        double total = 1;
        for (int k = 0; k < Dim; ++k) {
            const double range = std::max(high_[k] - low_[k], 0.0);
            cells_[k] = static_cast<std::int64_t>(std::floor(range / side[k])) + 1;
            total *= static_cast<double>(cells_[k] + 2);
        }
        if (total <= cell_limit) break;
        for (int k = 0; k < Dim; ++k) side[k] *= 1.25;
    }
    std::int64_t stride = 1;
    for (int k = 0; k < Dim; ++k) {
        inverse_side_[k] = 1 / side[k];
        stride_[k] = stride;
        stride *= cells_[k] + 2;
    }
    cell_total_ = static_cast<std::size_t>(stride);
}

// A counting sort: count per cell, prefix sums, then each record goes to the next free slot of
// its cell. cell_begin_[c + 1] serves as cell c's fill position, so that when the fill ends it
// holds cell c's end, which is cell c + 1's begin: no second array.
template <int Dim>
void UniformGrid<Dim>::sort_into_cells(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids) {
    cell_of_box_.resize(boxes.size());
    cell_begin_.assign(cell_total_ + 2, 0);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (is_oversized(boxes[i])) {
            cell_of_box_[i] = not_in_grid;
            continue;
        }
        const Index cell = flat_cell(boxes[i].min);
        cell_of_box_[i] = cell;
        ++cell_begin_[cell + 2];
    }
    for (std::size_t c = 2; c < cell_begin_.size(); ++c) cell_begin_[c] += cell_begin_[c - 1];
    records_.resize(boxes.size() - oversized_ids_.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Index cell = cell_of_box_[i];
        if (cell == not_in_grid) continue;
        records_[cell_begin_[cell + 1]++] = record_of(boxes[i], ids[i]);
    }
}

// Each cell against itself and its upper-half neighbours: (+1, 0, 0), (-1..1, +1, 0) and
// (-1..1, -1..1, +1) in 3D; (+1, 0) and (-1..1, +1) in 2D. A pair of overlapping boxes whose
// lower corners lie in cells a and b is tested from a if b - a is in that half, from b otherwise.
// A box whose upper corner stays in its own cell on an axis cannot overlap a box whose lower
// corner lies in the next cell on that axis (the cell coordinate is monotone), so those
// neighbours are skipped for it: about 40% of the tests on boxes of similar size.
template <int Dim>
void UniformGrid<Dim>::pairs_in_cells(std::vector<Pair>& pairs) const {
    const Index* begin = cell_begin_.data();
    const Record* records = records_.data();
    auto test_range = [&](const Query& query, BoxId id, Index from, Index to) {
        for (Index j = from; j < to; ++j)
            if (overlap(query, records[j])) pairs.push_back(ordered_pair(id, records[j].id));
    };
    // Cells [cell - 1, cell + 1] of a neighbour row, the last one only when the box reaches it.
    auto test_row = [&](const Query& query, BoxId id, std::int64_t cell, std::int64_t reaches_x) {
        test_range(query, id, begin[cell - 1], begin[cell + 1 + reaches_x]);
    };
    auto visit_row = [&](std::int64_t row_start, std::array<std::int64_t, Dim> at) {
        for (std::int64_t x = 1; x <= cells_[0]; ++x) {
            const std::int64_t cell = row_start + x;
            const Index first = begin[cell], end = begin[cell + 1];
            if (first == end) continue;
            at[0] = x;
            for (Index i = first; i < end; ++i) {
                const Query a = query_of(records[i]);
                const BoxId id = records[i].id;
                std::array<std::int64_t, Dim> reaches{};
                for (int k = 0; k < Dim; ++k) reaches[k] = lower_corner_coordinate(a.lanes[k], k) + 1 > at[k];
                test_range(a, id, i + 1, begin[cell + 1 + reaches[0]]);
                if (reaches[1]) test_row(a, id, cell + stride_[1], reaches[0]);
                if constexpr (Dim == 3) {
                    if (!reaches[2]) continue;
                    test_row(a, id, cell + stride_[2] - stride_[1], reaches[0]);
                    test_row(a, id, cell + stride_[2], reaches[0]);
                    if (reaches[1]) test_row(a, id, cell + stride_[2] + stride_[1], reaches[0]);
                }
            }
        }
    };
    if constexpr (Dim == 3) {
        for (std::int64_t z = 1; z <= cells_[2]; ++z)
            for (std::int64_t y = 1; y <= cells_[1]; ++y) visit_row(z * stride_[2] + y * stride_[1], {0, y, z});
    } else {
        for (std::int64_t y = 1; y <= cells_[1]; ++y) visit_row(y * stride_[1], {0, y});
    }
}

// A grid box b overlapping oversized box o has b.min >= o.min - b's extent >= o.min - the largest
// extent, and b.min <= o.max: its lower corner lies in that window's cells.
template <int Dim>
void UniformGrid<Dim>::oversized_against_cells(std::vector<Pair>& pairs) const {
    const Index* begin = cell_begin_.data();
    for (std::size_t o = 0; o < oversized_boxes_.size(); ++o) {
        const BenchBox<Dim>& box = oversized_boxes_[o];
        const Query query = query_of(box.min, box.max);
        std::array<std::int64_t, Dim> from{}, to{};
        for (int k = 0; k < Dim; ++k) {
            from[k] = cell_coordinate(static_cast<double>(box.min[k]) - largest_extent_[k], k) + 1;
            to[k] = cell_coordinate(box.max[k], k) + 1;
        }
        auto test_row = [&](std::int64_t row_start) {
            for (Index j = begin[row_start + from[0]]; j < begin[row_start + to[0] + 1]; ++j)
                if (overlap(query, records_[j])) pairs.push_back(ordered_pair(oversized_ids_[o], records_[j].id));
        };
        if constexpr (Dim == 3) {
            for (std::int64_t z = from[2]; z <= to[2]; ++z)
                for (std::int64_t y = from[1]; y <= to[1]; ++y) test_row(z * stride_[2] + y * stride_[1]);
        } else {
            for (std::int64_t y = from[1]; y <= to[1]; ++y) test_row(y * stride_[1]);
        }
    }
}

template class UniformGrid<2>;
template class UniformGrid<3>;

}  // namespace smb::bench
