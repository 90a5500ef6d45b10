// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

// The textbook grid, a second scheme beside uniform_grid_peer.cpp: every box is registered in
// every cell it overlaps, every pair of a cell is tested, and a pair that several cells share is
// kept by one of them. Cells are twice the mean box size (the usual rule of thumb: most boxes
// touch 2^Dim cells or fewer), grown until there are at most about two cells per box so that
// memory stays O(N).
constexpr double cell_to_box_ratio = 2.0;
constexpr double cells_per_box_limit = 2.0;

template <int Dim>
class UniformGridEveryCellPeer final : public StatelessPeer<Dim> {
protected:
    void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        pairs.clear();
        if (step.size() == 0) return;
        lay_out_grid(step.boxes);
        bin_boxes(step.boxes);
        report_pairs(step, pairs);
    }

private:
    void lay_out_grid(std::span<const BenchBox<Dim>> boxes) {
        double mean_side = 0;
        for (int k = 0; k < Dim; ++k) {
            origin_[k] = boxes[0].min[k];
            double high = boxes[0].max[k];
            for (const auto& box : boxes) {
                origin_[k] = std::min<double>(origin_[k], box.min[k]);
                high = std::max<double>(high, box.max[k]);
            }
            extent_[k] = high - origin_[k];
        }
        for (const auto& box : boxes) {
            double largest = 0;
            for (int k = 0; k < Dim; ++k) largest = std::max<double>(largest, box.max[k] - box.min[k]);
            mean_side += largest;
        }
        mean_side /= static_cast<double>(boxes.size());
        double cell = std::max(cell_to_box_ratio * mean_side, 1e-6);
        const double cell_limit = cells_per_box_limit * static_cast<double>(boxes.size()) + 64;
        for (;;) {
            double total = 1;
            for (int k = 0; k < Dim; ++k) {
                cells_per_axis_[k] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent_[k] / cell)));
                total *= static_cast<double>(cells_per_axis_[k]);
            }
            if (total <= cell_limit) break;
            cell *= 1.25;
        }
        inverse_cell_ = 1.0 / cell;
        cell_count_ = 1;
        for (int k = 0; k < Dim; ++k) cell_count_ *= static_cast<std::size_t>(cells_per_axis_[k]);
    }

    // Monotone in `value`, so a point inside a box always maps into the box's cell range.
    [[nodiscard]] std::int64_t cell_coordinate(float value, int axis) const {
        const auto raw = static_cast<std::int64_t>(std::floor((value - origin_[axis]) * inverse_cell_));
        return std::clamp<std::int64_t>(raw, 0, cells_per_axis_[axis] - 1);
    }

    [[nodiscard]] std::size_t flat_index(const std::array<std::int64_t, Dim>& coordinate) const {
        std::size_t index = 0;
        for (int k = Dim - 1; k >= 0; --k)
            index = index * static_cast<std::size_t>(cells_per_axis_[k]) + static_cast<std::size_t>(coordinate[k]);
        return index;
    }

    template <typename Visit>
    void for_each_cell_of(const BenchBox<Dim>& box, Visit&& visit) const {
        std::array<std::int64_t, Dim> low{}, high{}, at{};
        for (int k = 0; k < Dim; ++k) {
            low[k] = cell_coordinate(box.min[k], k);
            high[k] = cell_coordinate(box.max[k], k);
        }
        at = low;
        for (;;) {
            visit(flat_index(at));
            int k = 0;
            while (k < Dim && at[k] == high[k]) {
                at[k] = low[k];
                ++k;
            }
            if (k == Dim) return;
            ++at[k];
        }
    }

    // Counting sort of (cell, box) entries: one pass counts, a prefix sum places, one fills.
    void bin_boxes(std::span<const BenchBox<Dim>> boxes) {
        cell_start_.assign(cell_count_ + 1, 0);
        for (const auto& box : boxes) for_each_cell_of(box, [&](std::size_t cell) { ++cell_start_[cell + 1]; });
        for (std::size_t c = 0; c < cell_count_; ++c) cell_start_[c + 1] += cell_start_[c];
        entries_.resize(cell_start_[cell_count_]);
        fill_at_.assign(cell_start_.begin(), cell_start_.end() - 1);
        for (std::size_t i = 0; i < boxes.size(); ++i)
            for_each_cell_of(boxes[i],
                             [&](std::size_t cell) { entries_[fill_at_[cell]++] = static_cast<std::uint32_t>(i); });
    }

    // A pair shared by several cells is reported only in the cell holding the lower corner of
    // the two boxes' intersection, which both boxes cover.
    void report_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) const {
        for (std::size_t cell = 0; cell < cell_count_; ++cell) {
            const std::size_t begin = cell_start_[cell], end = cell_start_[cell + 1];
            for (std::size_t a = begin; a < end; ++a) {
                const BenchBox<Dim>& first = step.boxes[entries_[a]];
                for (std::size_t b = a + 1; b < end; ++b) {
                    const BenchBox<Dim>& second = step.boxes[entries_[b]];
                    if (!overlaps(first, second)) continue;
                    std::array<std::int64_t, Dim> corner{};
                    for (int k = 0; k < Dim; ++k) corner[k] = cell_coordinate(std::max(first.min[k], second.min[k]), k);
                    if (flat_index(corner) == cell)
                        pairs.push_back(ordered_pair(step.ids[entries_[a]], step.ids[entries_[b]]));
                }
            }
        }
    }

    std::array<double, Dim> origin_{};
    std::array<double, Dim> extent_{};
    std::array<std::int64_t, Dim> cells_per_axis_{};
    double inverse_cell_ = 1;
    std::size_t cell_count_ = 0;
    std::vector<std::uint32_t> cell_start_;
    std::vector<std::uint32_t> fill_at_;
    std::vector<std::uint32_t> entries_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_uniform_grid_every_cell_peer() {
    return std::make_unique<UniformGridEveryCellPeer<Dim>>();
}

template std::unique_ptr<Peer<2>> make_uniform_grid_every_cell_peer<2>();
template std::unique_ptr<Peer<3>> make_uniform_grid_every_cell_peer<3>();

}  // namespace smb::bench
