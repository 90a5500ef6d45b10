// SPDX-License-Identifier: MIT
#pragma once
// The first planes of the levels above the columns, cut from an evenly spaced sample of the
// caller's boxes before the boxes are copied, where the cuts have no planes yet (the first
// detection, a new number of segments, a new origin).
//
// Without planes the boxes are copied in slot order, which follows no cell, and every level
// after the first and every cell check then reads its boxes from all over the copy: at 1M
// boxes in 3D the first detection took twice a later one, most of it waiting for memory. With
// planes cut before the copy, the order is counting-sorted by column (column_presort.hpp) and
// the copy lays each column out in one run, as a later detection has it. The sample makes
// cutting cheap: a few passes over a quarter of the boxes at 1M in 3D, against a pass over the
// boxes per level. Its planes are as even as the levels' own sampled cuts (kSamplePerSegment
// keys per segment); each group's band is set from the sample's counts scaled to the boxes,
// and a group whose real counts leave it is cut again by the levels from all its entries.
// Exactness never depends on the planes (cut_tree.hpp), only speed does.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/held_box.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/quantile_select.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim, std::floating_point Input>
class SampledCuts {
public:
    /// Cuts every group of levels 0 .. Dim-2 of `cuts` (which has its number of segments and no
    /// planes) from a sample of `input`, held from `origin` where Real rounds Input, and sets
    /// their bands. The deepest level is left to the levels (cut there, or kept whole as columns).
    void cut(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin, CutTree<Real, Dim>& cuts) {
        const std::size_t n = input.size();
        const std::uint32_t k = cuts.segments();
        if (n == 0 || k == 0) return;
        take_sample(input, origin, sample_size(n, k));
        const double scale = static_cast<double>(n) / static_cast<double>(boxes_.size());
        // Level 0 holds every sampled box in its one group.
        begin_.assign({0, static_cast<std::uint32_t>(boxes_.size())});
        for (int level = 0; level + 1 < Dim; ++level) {
            const int axis = CutTree<Real, Dim>::axis_of_level(level);
            const std::size_t groups = cuts.groups(level);
            ranges_.resize(boxes_.size());
            counts_.assign(groups * k + 1, 0U);
            for (std::size_t g = 0; g < groups; ++g) {
                const Box<Real, Dim>* group = boxes_.data() + begin_[g];
                const std::size_t size = begin_[g + 1] - begin_[g];
                cuts.cut_group(
                    level, g, size, [&](std::size_t i) { return group[i].min[axis]; },
                    [&](std::size_t i) { return group[i].max[axis] - group[i].min[axis]; }, selector_);
                // The group's segments as the levels will find them, for its band and the next level.
                const std::span<const Real> planes = cuts.cuts(level, g);
                std::uint32_t* count = counts_.data() + g * k + 1;
                std::uint32_t* ranges = ranges_.data() + begin_[g];
                for (std::size_t i = 0; i < size; ++i) {
                    const std::uint32_t lo = segment_of(planes, group[i].min[axis]);
                    const std::uint32_t hi = segment_of_max(planes, group[i].max[axis], lo);
                    // A box spanning more than two segments leaves the levels (oversized).
                    const bool oversized = hi - lo > 1;
                    ranges[i] = oversized ? kNone : lo | (hi << 16);
                    count[lo] += oversized ? 0U : 1U;
                    count[hi] += !oversized && hi != lo ? 1U : 0U;
                }
                std::size_t registrations = 0;
                std::uint32_t fullest = 0;
                for (std::uint32_t s = 0; s < k; ++s) {
                    registrations += count[s];
                    fullest = std::max(fullest, count[s]);
                }
                cuts.set_band(level, g, static_cast<std::size_t>(static_cast<double>(registrations) * scale),
                              static_cast<std::uint32_t>(static_cast<double>(fullest) * scale));
            }
            if (level + 2 < Dim) regroup(groups, k);
        }
        release();
    }

private:
    static constexpr std::uint32_t kNone = 1;  // first segment 1, last 0: registered nowhere

    /// As many boxes as the levels' own sampled cuts read keys (kSamplePerSegment per segment
    /// in every group of the level above the columns), or all of them where that is most.
    [[nodiscard]] static std::size_t sample_size(std::size_t n, std::uint32_t k) {
        std::size_t size = CutTree<Real, Dim>::kSamplePerSegment;
        for (int level = 0; level + 1 < Dim; ++level) size *= k;
        return size * 2 >= n ? n : size;
    }

    void take_sample(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin, std::size_t size) {
        const std::size_t n = input.size();
        boxes_.resize(size);
        // Box floor(i n / size), stepped without a division per box.
        const std::size_t step = n / size;
        const std::size_t carry = n % size;
        std::size_t at = 0;
        std::size_t remainder = 0;
        for (std::size_t i = 0; i < size; ++i, at += step, remainder += carry) {
            if (remainder >= size) {
                remainder -= size;
                ++at;
            }
            const Box<Input, Dim>& box = input[at];
            if constexpr (std::is_same_v<Real, Input>) {
                (void)origin;
                boxes_[i] = box;
            } else {
                boxes_[i] = held_box<Input, Dim>(box, origin);
            }
        }
    }

    /// The next level's groups: a copy of each sampled box in every segment its range touches,
    /// by a counting sort (counts_: registrations per segment, shifted by one). Copies, so that
    /// the next level reads each group's boxes in one run.
    void regroup(std::size_t groups, std::uint32_t k) {
        for (std::size_t s = 0; s < groups * k; ++s) counts_[s + 1] += counts_[s];
        next_.resize(counts_.back());
        for (std::size_t g = 0; g < groups; ++g) {
            std::uint32_t* cursor = counts_.data() + g * k;
            for (std::uint32_t i = begin_[g]; i < begin_[g + 1]; ++i) {
                const std::uint32_t lo = ranges_[i] & 0xFFFFU;
                const std::uint32_t hi = ranges_[i] >> 16;
                if (lo > hi) continue;
                next_[cursor[lo]++] = boxes_[i];
                if (hi != lo) next_[cursor[hi]++] = boxes_[i];
            }
        }
        // The cursors have moved each segment's offset to the next one's: shift them back.
        begin_.assign(groups * k + 1, 0U);
        std::copy(counts_.begin(), counts_.begin() + static_cast<std::ptrdiff_t>(groups * k), begin_.begin() + 1);
        boxes_.swap(next_);
    }

    void release() {
        boxes_ = {};
        next_ = {};
        ranges_ = {};
    }

    std::vector<Box<Real, Dim>> boxes_;  // the sampled boxes registered in each group, group by group
    std::vector<Box<Real, Dim>> next_;   // the next level's, while they are regrouped
    std::vector<std::uint32_t> begin_;   // group g's boxes are [begin_[g], begin_[g + 1])
    std::vector<std::uint32_t> ranges_;  // per box: first | last segment << 16 (kNone: oversized)
    std::vector<std::uint32_t> counts_;  // registrations per segment of the level, shifted by one
    QuantileSelector<Real> selector_;
};

}  // namespace smb::detail
