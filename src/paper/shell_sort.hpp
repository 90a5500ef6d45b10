// SPDX-License-Identifier: MIT
#pragma once
// The diminishing increment sort (DIS) of the paper's Section 2.2: Shell's sort with the
// increments 2^k - 1 (..., 15, 7, 3, 1). Between two steps a persistent list is almost sorted,
// so the final insertion pass (increment 1) runs in about linear time; the larger increments
// move items that travelled far in fewer moves. The paper picks the number of increments t
// adaptively but does not say how; our rule is in DisController below.

#include <algorithm>
#include <cstddef>
#include <span>

#include "paper/axis_entry.hpp"

namespace smb::detail {

/// Work one DIS call did, for the adaptive rule and the statistics.
struct DisWork {
    std::size_t items = 0;
    std::size_t coarse_moves = 0;  ///< shifts made by the passes with increment > 1
    std::size_t fine_moves = 0;    ///< shifts made by the final insertion pass
    /// Key comparisons: one per item per pass, plus one per shift (at most: a shift that brings an
    /// item to the front of its section is not followed by one).
    std::size_t comparisons = 0;
    bool fell_back = false;          ///< the move budget ran out and the list was introsorted
    std::size_t fallback_items = 0;  ///< items of the lists that were introsorted

    DisWork& operator+=(const DisWork& other) noexcept {
        items += other.items;
        coarse_moves += other.coarse_moves;
        fine_moves += other.fine_moves;
        comparisons += other.comparisons;
        fell_back = fell_back || other.fell_back;
        fallback_items += other.fallback_items;
        return *this;
    }
    [[nodiscard]] std::size_t moves() const noexcept { return coarse_moves + fine_moves; }
};

/// One insertion-sort pass over the elements `gap` apart. Returns false when it has made more
/// than `budget` shifts; the list is then still a permutation of its items, only not sorted.
template <std::floating_point Real>
bool gapped_insertion_pass(std::span<AxisEntry<Real>> list, std::size_t gap, std::size_t budget, std::size_t& moves) {
    const std::size_t n = list.size();
    for (std::size_t i = gap; i < n; ++i) {
        if (!entry_less(list[i], list[i - gap])) continue;
        const AxisEntry<Real> value = list[i];
        std::size_t j = i;
        do {
            list[j] = list[j - gap];
            j -= gap;
            ++moves;
        } while (j >= gap && entry_less(value, list[j - gap]));
        list[j] = value;
        if (moves > budget) return false;
    }
    return true;
}

/// DIS with `increments` increments (2^increments - 1 down to 1). The move budget keeps a list
/// that is far from sorted (boxes that jumped) from costing Shell sort's superlinear worst case:
/// past about 8 moves per item per pass, introsort finishes the job in O(n log n).
template <std::floating_point Real>
DisWork diminishing_increment_sort(std::span<AxisEntry<Real>> list, int increments) {
    DisWork work;
    work.items = list.size();
    if (list.size() < 2) return work;
    const std::size_t budget = 8 * list.size() + 64;
    for (int k = increments; k >= 1; --k) {
        const std::size_t gap = (std::size_t{1} << k) - 1;
        if (gap >= list.size()) continue;
        std::size_t& moves = k == 1 ? work.fine_moves : work.coarse_moves;
        std::size_t pass_moves = 0;
        const bool finished = gapped_insertion_pass(list, gap, budget, pass_moves);
        moves += pass_moves;
        work.comparisons += list.size() - gap + pass_moves;
        if (!finished) {
            std::sort(list.begin(), list.end(), EntryLess{});
            work.fell_back = true;
            work.fallback_items = list.size();
            return work;
        }
    }
    return work;
}

/// The adaptive choice of t, the number of increments, kept per level from step to step.
/// After each step: if the final insertion pass shifted items more than two places on average
/// (or a section needed the fallback), the list is more disordered than t increments handle
/// cheaply, so t grows; if the coarse passes found almost nothing to move (under one item in
/// twenty), they cost a full pass each for nothing, so t shrinks. t = 1 is plain insertion
/// sort, the right choice for the small motions of most simulation steps.
class DisController {
public:
    static constexpr int kMaxIncrements = 16;

    [[nodiscard]] int increments() const noexcept { return increments_; }

    void learn(const DisWork& work) noexcept {
        if (work.items == 0) return;
        const double fine_per_item = static_cast<double>(work.fine_moves) / static_cast<double>(work.items);
        const double coarse_per_item = static_cast<double>(work.coarse_moves) / static_cast<double>(work.items);
        if (work.fell_back || fine_per_item > 2.0) {
            increments_ = std::min(increments_ + 1, kMaxIncrements);
        } else if (increments_ > 1 && coarse_per_item < 0.05) {
            --increments_;
        }
    }

private:
    int increments_ = 1;
};

}  // namespace smb::detail
