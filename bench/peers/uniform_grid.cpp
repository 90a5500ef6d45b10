// SPDX-License-Identifier: MIT
#include "peers/uniform_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "peers/peer.hpp"

namespace smb::bench {
namespace {

// A box is oversized when an extent exceeds this multiple of that axis's 95th percentile.
constexpr double oversize_factor = 2.0;
constexpr double oversize_quantile = 0.95;
constexpr std::size_t sample_size = 1024;
// Cells per axis at most: the coordinates stay exact in float.
constexpr double most_cells_per_axis = 0x1p20;
// Positions the gather reads ahead of the one it copies.
constexpr std::size_t prefetch_ahead = 16;
// Below this many boxes a second thread costs more than it saves.
constexpr std::size_t threads_from = 4096;
constexpr std::uint32_t not_in_cells = std::numeric_limits<std::uint32_t>::max();

/// The largest of these differences rounded up to a float: no extent exceeds it.
float rounded_up(double extent) {
    auto rounded = static_cast<float>(extent);
    if (static_cast<double>(rounded) < extent)
        rounded = std::nextafter(rounded, std::numeric_limits<float>::infinity());
    return rounded;
}

/// Appends the hits of one run of positions, [from, to), after the `used` first of `hits`, which
/// has room for every position (a box's runs never share one) and 2 Lanes more.
template <std::size_t Lanes, int Dim>
[[gnu::always_inline]] inline std::size_t append_hits(const grid_lanes::Columns<Dim>& columns,
                                                      const grid_lanes::Query<Lanes, Dim>& query, std::uint32_t from,
                                                      std::uint32_t to, std::vector<std::uint32_t>& hits,
                                                      std::size_t used) {
    return static_cast<std::size_t>(grid_lanes::test_run<Lanes, Dim>(columns, query, from, to, hits.data() + used) -
                                    hits.data());
}

}  // namespace

template <int Dim>
struct UniformGrid<Dim>::IdSink {
    const BoxId* ids = nullptr;
    std::vector<Pair>* pairs = nullptr;
    void emit(Index position, const Index* hit, const Index* end) const {
        const BoxId id = ids[position];
        for (; hit != end; ++hit) {
            const BoxId other = ids[*hit];
            pairs->push_back(Pair{std::min(id, other), std::max(id, other)});
        }
    }
};

template <int Dim>
struct UniformGrid<Dim>::PositionSink {
    std::vector<PositionPair>* pairs = nullptr;
    void emit(Index position, const Index* hit, const Index* end) const {
        for (; hit != end; ++hit) pairs->push_back(PositionPair{position, *hit});
    }
};

template <int Dim>
UniformGrid<Dim>::UniformGrid(Shape shape, int threads)
    : shape_(shape), threads_(std::clamp(threads, 1, 2)), lanes_(grid_lanes::best_lanes()) {}

template <int Dim>
void UniformGrid<Dim>::find_pairs(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids,
                                  std::vector<Pair>& pairs) {
    arrange(boxes, ids);
    second_thread_pairs_.clear();
    std::array<IdSink, 2> sinks{IdSink{ids_.data(), &pairs}, IdSink{ids_.data(), &second_thread_pairs_}};
    run_threads(sinks);
    pairs.insert(pairs.end(), second_thread_pairs_.begin(), second_thread_pairs_.end());
    if (oversized_boxes_.empty()) return;
    if (!oversized_grid_) oversized_grid_ = std::make_unique<UniformGrid>(shape_, 1);
    oversized_grid_->find_pairs(oversized_boxes_, oversized_ids_, pairs);
}

template <int Dim>
void UniformGrid<Dim>::find_position_pairs(std::span<const BenchBox<Dim>> boxes, std::vector<PositionPair>& pairs) {
    arrange(boxes, {});
    second_thread_position_pairs_.clear();
    std::array<PositionSink, 2> sinks{PositionSink{&pairs}, PositionSink{&second_thread_position_pairs_}};
    run_threads(sinks);
    pairs.insert(pairs.end(), second_thread_position_pairs_.begin(), second_thread_position_pairs_.end());
    if (oversized_boxes_.empty()) return;
    if (!oversized_grid_) oversized_grid_ = std::make_unique<UniformGrid>(shape_, 1);
    oversized_pairs_.clear();
    oversized_grid_->find_position_pairs(oversized_boxes_, oversized_pairs_);
    const auto nested_order = oversized_grid_->order();
    const auto first = static_cast<Index>(grid_count_);
    for (const PositionPair& pair : oversized_pairs_)
        pairs.push_back(PositionPair{first + nested_order[pair.a], first + nested_order[pair.b]});
}

template <int Dim>
void UniformGrid<Dim>::arrange(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids) {
    oversized_boxes_.clear();
    oversized_ids_.clear();
    order_.clear();
    grid_count_ = 0;
    if (boxes.empty()) return;
    choose_oversize_limits(boxes);
    measure(boxes);
    if (grid_count_ < boxes.size() / 2) {
        // The sample misjudged the sizes: no box is oversized then.
        oversize_limit_.fill(std::numeric_limits<float>::infinity());
        measure(boxes);
    }
    lay_out(grid_count_);
    sort_into_cells(boxes);
    const std::size_t count = boxes.size();
    for (int k = 0; k < Dim; ++k) {
        min_[k].resize(count + padding);
        max_[k].resize(count + padding);
    }
    ids_.resize(ids.empty() ? 0 : count);
    if (threads_ > 1 && count >= threads_from) {
        std::thread second([&] { gather(boxes, ids, count / 2, count); });
        gather(boxes, ids, 0, count / 2);
        second.join();
    } else {
        gather(boxes, ids, 0, count);
    }
    for (std::size_t p = grid_count_; p < count; ++p) {
        oversized_boxes_.push_back(boxes[order_[p]]);
        if (!ids.empty()) oversized_ids_.push_back(ids[order_[p]]);
    }
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

// The lowest lower corner and the largest extent of the boxes that go into the cells.
template <int Dim>
void UniformGrid<Dim>::measure(std::span<const BenchBox<Dim>> boxes) {
    std::array<float, Dim> low{}, high{};
    std::array<double, Dim> largest{};
    low.fill(std::numeric_limits<float>::infinity());
    high.fill(-std::numeric_limits<float>::infinity());
    std::size_t in_cells = 0;
    for (const BenchBox<Dim>& box : boxes) {
        if (is_oversized(box)) continue;
        ++in_cells;
        for (int k = 0; k < Dim; ++k) {
            low[k] = std::min(low[k], box.min[k]);
            high[k] = std::max(high[k], box.min[k]);
            // In double: the difference of two floats of similar size is exact there.
            largest[k] = std::max(largest[k], static_cast<double>(box.max[k]) - static_cast<double>(box.min[k]));
        }
    }
    grid_count_ = in_cells;
    for (int k = 0; k < Dim; ++k) {
        low_[k] = in_cells ? low[k] : 0.0f;
        // The margin covers a difference that was not exact in double.
        largest_extent_[k] = rounded_up(largest[k] * (1 + 0x1p-40));
        range_[k] = in_cells ? static_cast<double>(high[k]) - static_cast<double>(low[k]) : 0.0;
    }
}

template <int Dim>
void UniformGrid<Dim>::lay_out(std::size_t box_count) {
    std::array<double, Dim> side{};
    for (int k = 0; k < Dim; ++k) {
        const double multiple = k == 0 ? shape_.x_side : shape_.other_sides;
        side[k] = std::max({multiple * static_cast<double>(largest_extent_[k]), range_[k] / most_cells_per_axis,
                            static_cast<double>(std::numeric_limits<float>::min())});
    }
    const double cell_limit = shape_.cells_per_box * static_cast<double>(box_count) + 64;
    for (;;) {
        double total = 1;
        for (int k = 0; k < Dim; ++k) total *= std::floor(range_[k] / side[k]) + 1;
        if (total <= cell_limit) break;
        for (int k = 0; k < Dim; ++k) side[k] *= 1.25;
    }
    cell_total_ = 1;
    for (int k = 0; k < Dim; ++k) {
        cells_[k] = static_cast<std::size_t>(std::floor(range_[k] / side[k])) + 1;
        cell_total_ *= cells_[k];
        inverse_side_[k] = static_cast<float>(1 / side[k]);
        last_cell_[k] = static_cast<float>(cells_[k] - 1);
    }
}

// A counting sort: count per cell, prefix sums, then each box goes to the next free position of
// its cell. cell_begin_[c + 1] serves as cell c's fill position, so that when the fill ends it
// holds cell c's end, which is cell c + 1's begin: no second array. The oversized boxes follow.
template <int Dim>
void UniformGrid<Dim>::sort_into_cells(std::span<const BenchBox<Dim>> boxes) {
    cell_of_box_.resize(boxes.size());
    cell_begin_.assign(cell_total_ + 2, 0);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (is_oversized(boxes[i])) {
            cell_of_box_[i] = not_in_cells;
            continue;
        }
        const std::size_t cell = flat_cell(boxes[i].min);
        cell_of_box_[i] = static_cast<Index>(cell);
        ++cell_begin_[cell + 2];
    }
    for (std::size_t c = 2; c < cell_begin_.size(); ++c) cell_begin_[c] += cell_begin_[c - 1];
    order_.resize(boxes.size());
    auto next_oversized = static_cast<Index>(grid_count_);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Index cell = cell_of_box_[i];
        const Index position = cell == not_in_cells ? next_oversized++ : cell_begin_[cell + 1]++;
        order_[position] = static_cast<Index>(i);
    }
}

// The caller's boxes are read in cell order, which is random in memory: the box some positions
// ahead is prefetched, both its first and its last byte, since a box may straddle two lines.
template <int Dim>
void UniformGrid<Dim>::gather(std::span<const BenchBox<Dim>> boxes, std::span<const BoxId> ids, std::size_t from,
                              std::size_t to) {
    const Index* order = order_.data();
    for (std::size_t p = from; p < to; ++p) {
        if (p + prefetch_ahead < to) {
            const auto* ahead = reinterpret_cast<const char*>(&boxes[order[p + prefetch_ahead]]);
            __builtin_prefetch(ahead);
            __builtin_prefetch(ahead + sizeof(BenchBox<Dim>) - 1);
            if (!ids.empty()) __builtin_prefetch(&ids[order[p + prefetch_ahead]]);
        }
        const BenchBox<Dim>& box = boxes[order[p]];
        for (int k = 0; k < Dim; ++k) {
            min_[k][p] = box.min[k];
            max_[k][p] = box.max[k];
        }
        if (!ids.empty()) ids_[p] = ids[order[p]];
    }
}

template <int Dim>
template <class Sink>
void UniformGrid<Dim>::run_threads(std::array<Sink, 2>& sinks) {
    const std::size_t count = order_.size();
    if (threads_ > 1 && count >= threads_from) {
        std::thread second([&] { scan(sinks[1], count / 2, count, hits_[1]); });
        scan(sinks[0], 0, count / 2, hits_[0]);
        second.join();
    } else {
        scan(sinks[0], 0, count, hits_[0]);
    }
}

template <int Dim>
template <class Sink>
void UniformGrid<Dim>::scan(Sink& sink, std::size_t from, std::size_t to, std::vector<Index>& hits) const {
#if SMB_BENCH_WIDE_LANES
    if (lanes_ == 8) return scan_avx2(sink, from, to, hits);
#endif
    scan_in_lanes<4>(sink, from, to, hits);
}

template <int Dim>
template <class Sink>
[[gnu::target("avx2,popcnt")]] void UniformGrid<Dim>::scan_avx2(Sink& sink, std::size_t from, std::size_t to,
                                                                std::vector<Index>& hits) const {
    scan_in_lanes<8>(sink, from, to, hits);
}

// The boxes at positions [from, to), each against the runs of positions its window reaches (see
// the header); a box in the cells only against later rows and the rest of its own, an oversized
// box against every row of its window.
template <int Dim>
template <std::size_t Lanes, class Sink>
[[gnu::always_inline]] inline void UniformGrid<Dim>::scan_in_lanes(Sink& sink, std::size_t from, std::size_t to,
                                                                   std::vector<Index>& hits) const {
    const grid_lanes::Columns<Dim> columns = this->columns();
    hits.resize(order_.size() + 2 * Lanes);
    const Index* begin = cell_begin_.data();
    const std::size_t row_length = cells_[0];
    const std::size_t plane = Dim == 3 ? cells_[0] * cells_[1] : 0;
    for (std::size_t p = from; p < to; ++p) {
        std::array<float, Dim> min, max;
        std::array<Index, Dim> own, low, high;
        for (int k = 0; k < Dim; ++k) {
            min[k] = columns.min[k][p];
            max[k] = columns.max[k][p];
            own[k] = cell_of(min[k], k);
            low[k] = cell_of(min[k] - largest_extent_[k], k);
            high[k] = cell_of(max[k], k);
        }
        const auto query = grid_lanes::splat<Lanes, Dim>(min, max);
        std::size_t used = 0;
        // Positions [begin[row + low[0]], begin[row + high[0] + 1]) of the row starting at cell `row`.
        const auto first_in = [&](std::size_t row) { return begin[row + low[0]]; };
        const auto end_in = [&](std::size_t row) { return begin[row + high[0] + 1]; };
        if (p < grid_count_) {
            std::size_t row = own[1] * row_length + (Dim == 3 ? own[Dim - 1] * plane : 0);
            used = append_hits<Lanes, Dim>(columns, query, static_cast<Index>(p + 1), end_in(row), hits, used);
            for (Index y = own[1] + 1; y <= high[1]; ++y) {
                row += row_length;
                used = append_hits<Lanes, Dim>(columns, query, first_in(row), end_in(row), hits, used);
            }
            if constexpr (Dim == 3) {
                for (Index z = own[2] + 1; z <= high[2]; ++z) {
                    for (Index y = low[1]; y <= high[1]; ++y) {
                        const std::size_t next = z * plane + y * row_length;
                        used = append_hits<Lanes, Dim>(columns, query, first_in(next), end_in(next), hits, used);
                    }
                }
            }
        } else {
            const Index z_low = Dim == 3 ? low[Dim - 1] : 0, z_high = Dim == 3 ? high[Dim - 1] : 0;
            for (Index z = z_low; z <= z_high; ++z) {
                for (Index y = low[1]; y <= high[1]; ++y) {
                    const std::size_t row = z * plane + y * row_length;
                    used = append_hits<Lanes, Dim>(columns, query, first_in(row), end_in(row), hits, used);
                }
            }
        }
        sink.emit(static_cast<Index>(p), hits.data(), hits.data() + used);
    }
}

template <int Dim>
void UniformGrid<Dim>::find_overlapping(const BenchBox<Dim>& box, std::vector<Index>& positions) const {
    if (order_.empty()) return;
    const grid_lanes::Columns<Dim> columns = this->columns();
    const auto query = grid_lanes::splat<4, Dim>(box.min, box.max);
    std::array<Index, Dim> low, high;
    for (int k = 0; k < Dim; ++k) {
        low[k] = cell_of(box.min[k] - largest_extent_[k], k);
        high[k] = cell_of(box.max[k], k);
    }
    const Index* begin = cell_begin_.data();
    const Index z_low = Dim == 3 ? low[Dim - 1] : 0, z_high = Dim == 3 ? high[Dim - 1] : 0;
    const auto row_of = [&](Index y, Index z) { return (Dim == 3 ? z * cells_[1] : 0) * cells_[0] + y * cells_[0]; };
    // Room for every candidate first: the runs write up to 8 slots past their hits.
    std::size_t candidates = order_.size() - grid_count_ + 8;
    for (Index z = z_low; z <= z_high; ++z)
        for (Index y = low[1]; y <= high[1]; ++y)
            candidates += begin[row_of(y, z) + high[0] + 1] - begin[row_of(y, z) + low[0]] + 8;
    std::size_t used = positions.size();
    positions.resize(used + candidates);
    for (Index z = z_low; z <= z_high; ++z) {
        for (Index y = low[1]; y <= high[1]; ++y) {
            const std::size_t row = row_of(y, z);
            used = append_hits<4, Dim>(columns, query, begin[row + low[0]], begin[row + high[0] + 1], positions, used);
        }
    }
    used = append_hits<4, Dim>(columns, query, static_cast<Index>(grid_count_), static_cast<Index>(order_.size()),
                               positions, used);
    positions.resize(used);
}

template class UniformGrid<2>;
template class UniformGrid<3>;

}  // namespace smb::bench
