// SPDX-License-Identifier: MIT
#pragma once
// The first planes of the levels above the columns, cut from an evenly spaced sample of the
// caller's boxes before they are copied, where the cuts have none (the first detection, a new
// number of segments, a new origin).
//
// Without planes the boxes are copied in slot order, which follows no cell, and every later pass
// reads them from all over the copy: at 1M boxes in 3D the first detection took twice a later
// one, mostly waiting for memory. With planes, the boxes are copied grouped by column
// (CellOrder::copy_by_column()), as a later detection has them. The sample makes cutting cheap:
// two passes over a quarter of the boxes at 1M in 3D, each kept only as its interval on the
// axis cut, against a pass over every box per level. Its planes are as even as the levels' own
// sampled cuts; each group's band is set from the sample's counts scaled to the boxes, and a
// group whose real counts leave it is cut again by the levels. Only speed depends on the planes.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/held_box.hpp"
#include "core/tuning.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/quantile_select.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim, std::floating_point Input>
class SampledCuts {
public:
    static_assert(Dim == 2 || Dim == 3, "one or two levels above the columns");

    /// Cuts every group of levels 0 .. Dim-2 of `cuts` (which has its number of segments and no
    /// planes) from a sample of `input`, held from `origin` where Real rounds Input, and sets
    /// their bands. The deepest level is left to the levels (cut there, or kept whole as columns).
    void cut(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin, CutTree<Real, Dim>& cuts) {
        if (input.empty() || cuts.cells() == 0) return;
        cut_levels(input, origin, cuts);
        if constexpr (Dim == 3) {
            const std::array<std::uint32_t, Dim> shape = reshaped(cuts);
            if (shape[0] != cuts.segments(0) || shape[1] != cuts.segments(1)) {
                cuts.reshape(shape);
                cut_levels(input, origin, cuts);
            }
        }
    }

    /// The shape the cuts should take where one of the two levels above the columns is a layer a
    /// few boxes thick: its planes, kept a box apart (CutTree::cut_group()), open fewer segments
    /// than it has, and every column holds as many times the target population. That level keeps
    /// the segments it can open and the other gets the rest, so that the columns number as many
    /// as before; a layer that opens only a few is left whole (tuning::whole_layer_open): its
    /// segments would be about a box thick, so that most boxes registered in two of them.
    /// `cuts`' own shape where both levels open most of their segments, or neither.
    [[nodiscard]] static std::array<std::uint32_t, Dim> reshaped(const CutTree<Real, Dim>& cuts) {
        std::array<std::uint32_t, Dim> shape{};
        for (int level = 0; level < Dim; ++level) shape[level] = cuts.segments(level);
        const std::array<double, 2> open{cuts.open_segments(0), cuts.open_segments(1)};
        const bool thin_first = open[0] < tuning::thin_level_open_share * shape[0];
        const bool thin_second = open[1] < tuning::thin_level_open_share * shape[1];
        if (thin_first == thin_second) return shape;
        const int layer = thin_first ? 0 : 1;
        const auto kept = open[layer] <= tuning::whole_layer_open
                              ? 1U
                              : static_cast<std::uint32_t>(std::max(1.0, std::round(open[layer])));
        const double columns = static_cast<double>(shape[0]) * static_cast<double>(shape[1]);
        shape[1 - layer] = static_cast<std::uint32_t>(
            std::min(std::round(columns / kept), static_cast<double>(CutTree<Real, Dim>::kMaxSegments)));
        shape[layer] = kept;
        return shape;
    }

private:
    using Interval = std::array<Real, 2>;  // min and max on one axis

    static constexpr int axis_of_level(int level) noexcept { return CutTree<Real, Dim>::axis_of_level(level); }

    /// Cuts every group of the levels above the columns from a sample of `input`.
    void cut_levels(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin,
                    CutTree<Real, Dim>& cuts) {
        const std::size_t n = input.size();
        const std::uint32_t k = cuts.segments(0);
        const std::size_t size = sample_size(n, cuts);
        const double scale = static_cast<double>(n) / static_cast<double>(size);
        // Level 0: one group of every sampled box, each held as its interval on the level's axis
        // only (the cut and the band need no more), a quarter of the box at 1M boxes in 3D.
        intervals_.resize(size);
        for_each_sampled(input, origin, size, [&](std::size_t i, const Box<Real, Dim>& box) {
            intervals_[i] = {box.min[axis_of_level(0)], box.max[axis_of_level(0)]};
        });
        begin_.assign({0, static_cast<std::uint32_t>(size)});
        cut_groups(0, cuts, scale);
        if constexpr (Dim == 3) {
            // Level 1: each sampled box's interval on its axis, in every group (slab) its
            // interval on level 0 touched, by a counting sort (counts_: shifted by one).
            for (std::size_t s = 0; s < k; ++s) counts_[s + 1] += counts_[s];
            next_.resize(counts_.back());
            std::uint32_t* cursor = counts_.data();
            for_each_sampled(input, origin, size, [&](std::size_t i, const Box<Real, Dim>& box) {
                const std::uint32_t lo = SegmentRange::lo_of(ranges_[i]);
                const std::uint32_t hi = SegmentRange::hi_of(ranges_[i]);
                if (lo > hi) return;
                const Interval interval{box.min[axis_of_level(1)], box.max[axis_of_level(1)]};
                next_[cursor[lo]++] = interval;
                if (hi != lo) next_[cursor[hi]++] = interval;
            });
            // The cursors moved each segment's offset to the next one's.
            begin_.assign(k + 1, 0U);
            std::copy(counts_.begin(), counts_.begin() + k, begin_.begin() + 1);
            intervals_.swap(next_);
            cut_groups(1, cuts, scale);
        }
    }

    /// As many boxes as the levels' own sampled cuts read keys (kSamplePerSegment per segment
    /// in every group of the level above the columns), or all of them where that is most.
    [[nodiscard]] static std::size_t sample_size(std::size_t n, const CutTree<Real, Dim>& cuts) {
        std::size_t size = CutTree<Real, Dim>::kSamplePerSegment;
        for (int level = 0; level + 1 < Dim; ++level) size *= cuts.segments(level);
        return size * 2 >= n ? n : size;
    }

    /// visit(i, held box) for the boxes floor(i n / size), i < size, stepped without a division.
    template <class Visit>
    static void for_each_sampled(std::span<const Box<Input, Dim>> input, const std::array<Input, Dim>& origin,
                                 std::size_t size, Visit&& visit) {
        const std::size_t n = input.size();
        const std::size_t step = n / size;
        const std::size_t carry = n % size;
        std::size_t at = 0;
        std::size_t remainder = 0;
        for (std::size_t i = 0; i < size; ++i, at += step, remainder += carry) {
            if (remainder >= size) {
                remainder -= size;
                ++at;
            }
            visit(i, held_as<Real>(input[at], origin));
        }
    }

    /// Cuts every group of `level` from its intervals, and sets its band from their segments,
    /// which ranges_ and counts_ (per segment, shifted by one) keep for the next level.
    void cut_groups(int level, CutTree<Real, Dim>& cuts, double scale) {
        const std::size_t groups = cuts.groups(level);
        const std::uint32_t k = cuts.segments(level);
        ranges_.resize(intervals_.size());
        counts_.assign(groups * k + 1, 0U);
        for (std::size_t g = 0; g < groups; ++g) {
            const Interval* group = intervals_.data() + begin_[g];
            const std::size_t size = begin_[g + 1] - begin_[g];
            cuts.cut_group(
                level, g, size, [&](std::size_t i) { return group[i][0]; },
                [&](std::size_t i) { return group[i][1] - group[i][0]; }, selector_);
            // The group's segments as the levels will find them.
            const std::span<const Real> planes = cuts.cuts(level, g);
            std::uint32_t* count = counts_.data() + g * k + 1;
            std::uint32_t* ranges = ranges_.data() + begin_[g];
            for (std::size_t i = 0; i < size; ++i) {
                const std::uint32_t lo = segment_of(planes, group[i][0]);
                const std::uint32_t hi = segment_of_max(planes, group[i][1], lo);
                // A box spanning more than two segments leaves the levels (oversized).
                const bool oversized = hi - lo > 1;
                ranges[i] = oversized ? SegmentRange::kNone : lo | (hi << 16);
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
    }

    std::vector<Interval> intervals_;    // the sampled boxes' intervals in each group, group by group
    std::vector<Interval> next_;         // the next level's, while they are regrouped
    std::vector<std::uint32_t> begin_;   // group g's intervals are [begin_[g], begin_[g + 1])
    std::vector<std::uint32_t> ranges_;  // per interval: a SegmentRange (kNone: oversized)
    std::vector<std::uint32_t> counts_;  // registrations per segment of the level, shifted by one
    QuantileSelector<Real> selector_;
};

}  // namespace smb::detail
