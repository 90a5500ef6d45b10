// SPDX-License-Identifier: MIT
#pragma once
// The axial cuts of the persistent-cut pipeline, kept from one detection to the next.
//
// Level l cuts along axis Dim-1-l (z, then y, then x in 3D), as the paper's levels do. Every
// group of level l (a slab for l = 1, a column for l = 2) is cut into the same number k of
// segments by k-1 cut values, so segment j of a group holds the coordinates v with
// cut[j-1] <= v < cut[j] (cut[-1] = -inf, cut[k-1] = +inf). Groups are numbered in
// (slab, column, ...) order: segment j of group g is group g*k + j of the next level, and the
// cells are the segments of the deepest level.
//
// The cut values are the paper's axial cut (equal numbers of boxes per segment) taken once and
// then kept while the segments stay balanced: boxes move a little each step, so last step's
// planes still split them about evenly, and keeping them turns the global sort of the paper's
// first list into a linear bucketing pass. A group is cut again when a segment outgrows the
// band its last cut allowed; exactness never depends on where the planes lie, only on every
// part of the pipeline locating a coordinate with the same segment_of().

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "core/tuning.hpp"
#include "cuts/quantile_select.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// Number of cut values <= value, i.e. the segment holding `value`. Boxes arrive in no particular
/// order relative to the planes, so a branching search would mispredict on almost every step.
/// Up to 64 planes a plain count is fastest (no dependent loads; the compiler vectorises it);
/// beyond, a branch-free binary search.
template <std::floating_point Real>
[[nodiscard]] [[gnu::always_inline]] inline std::uint32_t segment_of(std::span<const Real> cuts, Real value) noexcept {
    std::size_t n = cuts.size();
    const Real* base = cuts.data();
    if (n <= 64) {
        // A counter as wide as Real lets the compiler vectorise the comparisons.
        using Count = std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t>;
        Count count = 0;
        for (std::size_t i = 0; i < n; ++i) count += base[i] <= value ? Count{1} : Count{0};
        return static_cast<std::uint32_t>(count);
    }
    while (n > 1) {
        const std::size_t half = n / 2;
        base = (base[half] <= value) ? base + half : base;
        n -= half;
    }
    return static_cast<std::uint32_t>(base - cuts.data()) + (*base <= value ? 1U : 0U);
}

/// segment_of() when the answer is probably `hint` or a segment beside it: the entries of a
/// group arrive in last step's segment order and boxes move little, so the previous entry's
/// segment is nearly always right, and a box that crossed a plane since lies next to it.
/// `misses` counts the values that needed the full search.
template <std::floating_point Real>
[[nodiscard]] [[gnu::always_inline]] inline std::uint32_t segment_near(std::span<const Real> cuts, Real value,
                                                                       std::uint32_t hint,
                                                                       std::size_t& misses) noexcept {
    const std::size_t n = cuts.size();
    if (hint <= n) {
        if (hint == 0 || cuts[hint - 1] <= value) {
            if (hint == n || value < cuts[hint]) return hint;
            if (hint + 1 == n || value < cuts[hint + 1]) return hint + 1;
        } else if (hint == 1 || cuts[hint - 2] <= value) {
            return hint - 1;
        }
    }
    ++misses;
    return segment_of(cuts, value);
}

/// The segment of a box's max, given `lo`, its min's segment: lo, lo + 1, or lo + 2 standing
/// for any later one (a box that spans more than two segments leaves the levels, whichever its
/// last). `cuts` must be a group's planes from CutTree::cuts(), which are followed by two NaN,
/// so that the two planes after lo can be read without a bounds test, and a NaN never counts
/// as passed. No branch: whether a box crosses the plane after its min is a coin toss from one
/// box to the next (one in four at 1M in 3D) unless the boxes come sorted, which the cells
/// checked pair by pair do not leave them (cell_pairs.hpp).
template <std::floating_point Real>
[[nodiscard]] [[gnu::always_inline]] inline std::uint32_t segment_of_max(std::span<const Real> cuts, Real max,
                                                                         std::uint32_t lo) noexcept {
    const Real* next = cuts.data() + lo;
    const bool past_next = next[0] <= max;
    const bool past_after = next[1] <= max;
    return lo + (past_next ? 1U : 0U) + (past_next && past_after ? 1U : 0U);
}

/// The segments an entry touches: first | last << 16.
struct SegmentRange {
    static constexpr std::uint32_t lo_of(std::uint32_t range) noexcept { return range & 0xFFFFU; }
    static constexpr std::uint32_t hi_of(std::uint32_t range) noexcept { return range >> 16; }
    static constexpr std::uint32_t kNone = 1;  // first segment 1, last 0: registered nowhere
};

template <std::floating_point Real, int Dim>
class CutTree {
public:
    /// Most segments per group: a box's segment range is stored in two 16-bit halves.
    static constexpr std::uint32_t kMaxSegments = 65535;

    /// The axis level `level` cuts along.
    static constexpr int axis_of_level(int level) noexcept { return Dim - 1 - level; }

    /// Segments per group of `level` (0 before the first reshape()).
    [[nodiscard]] std::uint32_t segments(int level) const noexcept { return k_[level]; }
    [[nodiscard]] std::size_t groups(int level) const noexcept { return groups_[level]; }
    [[nodiscard]] std::size_t cells() const noexcept { return groups_[Dim]; }

    /// Sets the number of segments per group of every level; every group forgets its cuts when
    /// the shape changes.
    void reshape(std::array<std::uint32_t, Dim> shape) {
        for (std::uint32_t& segments : shape) segments = std::clamp<std::uint32_t>(segments, 1, kMaxSegments);
        if (shape == k_) return;
        k_ = shape;
        std::size_t groups = 1;
        for (int level = 0; level <= Dim; ++level) {
            groups_[level] = groups;
            if (level < Dim) {
                const std::uint32_t k = k_[level];
                cuts_[level].assign(groups * (k + 1), Real{0});
                // Two NaN past each group's planes: segment_of_max() reads them, and no
                // comparison with NaN holds.
                for (std::size_t g = 0; g < groups; ++g) {
                    cuts_[level][g * (k + 1) + k - 1] = std::numeric_limits<Real>::quiet_NaN();
                    cuts_[level][g * (k + 1) + k] = std::numeric_limits<Real>::quiet_NaN();
                }
                limit_[level].assign(groups, 0);  // 0: never cut
                groups *= k;
            }
        }
    }
    /// The same number of segments on every level.
    void reshape(std::uint32_t segments) {
        std::array<std::uint32_t, Dim> shape{};
        shape.fill(segments);
        reshape(shape);
    }

    /// The mean number of segments per group of `level` that its planes leave open (the planes
    /// dropped by cut_group() for lying closer than the boxes are thick end as +inf, and leave
    /// the segments past them empty).
    [[nodiscard]] double open_segments(int level) const noexcept {
        const std::uint32_t k = k_[level];
        std::size_t open = 0;
        for (std::size_t g = 0; g < groups_[level]; ++g) {
            const std::span<const Real> planes = cuts(level, g);
            open += 1 + static_cast<std::size_t>(std::count_if(planes.begin(), planes.end(), [](Real plane) {
                        return plane < std::numeric_limits<Real>::infinity();
                    }));
        }
        return groups_[level] == 0 || k == 0 ? 0.0 : static_cast<double>(open) / static_cast<double>(groups_[level]);
    }

    void forget() {
        k_ = {};
        for (int level = 0; level < Dim; ++level) {
            cuts_[level] = {};
            limit_[level] = {};
        }
        groups_ = {};
    }

    /// The k - 1 planes of a group, in order, followed in memory by two NaN (segment_of_max()).
    [[nodiscard]] std::span<const Real> cuts(int level, std::size_t group) const noexcept {
        return {cuts_[level].data() + group * (k_[level] + 1), k_[level] - 1};
    }

    /// True when group `group` of `level` must be cut (again) before its boxes are bucketed:
    /// it was never cut, or its fullest segment holds more than its band allows.
    [[nodiscard]] bool needs_cut(int level, std::size_t group, std::uint32_t fullest) const noexcept {
        const std::uint32_t limit = limit_[level][group];
        return limit == 0 || fullest > limit;
    }
    [[nodiscard]] bool was_cut(int level, std::size_t group) const noexcept { return limit_[level][group] != 0; }

    /// The axial cut: the keys in `selector` (the lower ends of the group's boxes; reordered)
    /// split into k segments of equal counts. Equal keys share a segment (a cut is a value), so a
    /// run of them may leave segments empty and one full. Planes closer than `min_gap` to the
    /// last one kept are dropped (space_planes()). The caller then sets the band (set_band()).
    void cut(int level, std::size_t group, QuantileSelector<Real>& selector, Real min_gap = Real{0}) {
        const std::uint32_t k = k_[level];
        Real* out = cuts_[level].data() + group * (k + 1);
        if (k > 1) {
            if (selector.keys.empty()) {
                std::fill(out, out + (k - 1), Real{0});
            } else {
                selector.select(k, out);
                if (min_gap > Real{0}) space_planes(out, k - 1, min_gap);
            }
        }
    }

    /// The axial cut of a group of n boxes, box j's lower end key_at(j) and its extent
    /// extent_at(j). The keys go into `selector`: all of them, or, past twice kSamplePerSegment
    /// per segment, those of boxes floor(i n / s), s = kSamplePerSegment * k. Deterministic; an
    /// order that aliases with the stride only makes the planes uneven, which the next cut
    /// corrects.
    ///
    /// Equal counts alone give segments thinner than the boxes in a layer a few boxes deep (a pile
    /// on a floor): most boxes would span more than two segments and leave the levels for the
    /// slow oversized check. So the planes are kept the group's typical extent apart (the upper
    /// quartile of a sample): the axis gets fewer, fuller segments. Boxes small against the
    /// segments (the usual case) drop no plane.
    template <class KeyAt, class ExtentAt>
    void cut_group(int level, std::size_t group, std::size_t n, KeyAt&& key_at, ExtentAt&& extent_at,
                   QuantileSelector<Real>& selector) {
        const std::size_t sample = kSamplePerSegment * k_[level];
        const std::size_t take = n > 2 * sample ? sample : n;
        std::vector<Real>& keys = selector.keys;
        keys.clear();
        for (std::size_t i = 0; i < take; ++i) keys.push_back(key_at(take == n ? i : i * n / take));
        std::array<Real, kExtentSample> extents{};
        const std::size_t sampled = std::min(n, kExtentSample);
        for (std::size_t i = 0; i < sampled; ++i) extents[i] = extent_at(i * n / sampled);
        Real min_gap{0};
        if (sampled > 0) {
            const auto quartile = extents.begin() + static_cast<std::ptrdiff_t>(sampled * 3 / 4);
            std::nth_element(extents.begin(), quartile, extents.begin() + static_cast<std::ptrdiff_t>(sampled));
            min_gap = *quartile;
        }
        cut(level, group, selector, min_gap);
    }

    /// The same with no spacing of the planes (extents of 0).
    template <class KeyAt>
    void cut_group(int level, std::size_t group, std::size_t n, KeyAt&& key_at, QuantileSelector<Real>& selector) {
        cut_group(
            level, group, n, key_at, [](std::size_t) { return Real{0}; }, selector);
    }

    /// Boxes sampled for a group's typical extent; keys per segment of a sampled cut.
    static constexpr std::size_t kExtentSample = tuning::extent_sample;
    static constexpr std::size_t kSamplePerSegment = tuning::sample_per_segment;

    /// Sets the band of a group just cut: its fullest segment may grow by half (and at least
    /// to twice the even share) before the group is cut again. Measuring the band on the fresh
    /// cut, not on the even share, keeps a group that cannot be balanced (a run of equal
    /// coordinates) from being cut again every step.
    void set_band(int level, std::size_t group, std::size_t registrations, std::uint32_t fullest) {
        const double even = static_cast<double>(registrations) / k_[level];
        const double band = std::max(2.0 * even, 1.5 * static_cast<double>(fullest)) + 8.0;
        limit_[level][group] = static_cast<std::uint32_t>(std::min(band, 4.0e9));
    }

    /// Leaves group `group` of `level` whole: every plane +inf, so that its first segment holds
    /// every box and the others stay empty, and the group is never cut again.
    void leave_whole(int level, std::size_t group) {
        const std::uint32_t k = k_[level];
        Real* out = cuts_[level].data() + group * (k + 1);
        if (k > 1) std::fill(out, out + (k - 1), std::numeric_limits<Real>::infinity());
        limit_[level][group] = std::numeric_limits<std::uint32_t>::max();
    }

    /// The group of the deepest level (a column where x is left uncut) that holds `box`'s
    /// lower corner.
    [[nodiscard]] std::uint32_t column_of(const Box<Real, Dim>& box) const noexcept {
        std::size_t group = 0;
        for (int level = 0; level + 1 < Dim; ++level)
            group = group * k_[level] + segment_of(cuts(level, group), box.min[axis_of_level(level)]);
        return static_cast<std::uint32_t>(group);
    }

    /// Lower plane of segment `segment` of group `group` (-inf for the first).
    [[nodiscard]] Real lower(int level, std::size_t group, std::uint32_t segment) const noexcept {
        return segment == 0 ? -std::numeric_limits<Real>::infinity()
                            : cuts_[level][group * (k_[level] + 1) + segment - 1];
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = 0;
        for (int level = 0; level < Dim; ++level)
            bytes += cuts_[level].capacity() * sizeof(Real) + limit_[level].capacity() * sizeof(std::uint32_t);
        return bytes;
    }

private:
    /// Keeps the first of `count` planes in order and each later one at least `min_gap` above
    /// the last one kept; the kept planes move to the front and +inf fills the rest, which no
    /// finite coordinate reaches (the segments past the last kept plane stay empty, and
    /// segment_of_max() never sees a repeated plane that would make a box span three segments).
    static void space_planes(Real* planes, std::uint32_t count, Real min_gap) {
        std::uint32_t kept = 0;
        for (std::uint32_t j = 0; j < count; ++j) {
            if (kept > 0 && !(planes[j] >= planes[kept - 1] + min_gap)) continue;
            planes[kept++] = planes[j];
        }
        std::fill(planes + kept, planes + count, std::numeric_limits<Real>::infinity());
    }

    std::array<std::uint32_t, Dim> k_{};  // segments per group of each level
    std::array<std::size_t, Dim + 1> groups_{};
    std::array<std::vector<Real>, Dim> cuts_;
    std::array<std::vector<std::uint32_t>, Dim> limit_;  // band of each group; 0 = not cut yet
};

}  // namespace smb::detail
