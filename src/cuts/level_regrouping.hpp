// SPDX-License-Identifier: MIT
#pragma once
// The levels of the persistent-cut pipeline: level l (axis Dim-1-l) registers every box of every
// group in each segment of the group its [min, max] touches (group_locator.hpp), by a stable
// counting sort: the singular regrouping of the paper, with its index array (the counts per
// segment, turned into offsets) and its stack array (the next free place of each segment). A
// group whose fullest segment left its band is cut again first (the axial cut, cut_tree.hpp). A
// box that spans more than two segments is oversized: it leaves the levels and is checked apart.
// The segments of the deepest level are the cells (cells.hpp).

#include <algorithm>
#include <array>
#include <atomic>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "core/bulk_vector.hpp"
#include "core/growth.hpp"
#include "core/stopwatch.hpp"
#include "core/thread_team.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/cells.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/group_locator.hpp"
#include "smb/box.hpp"
#include "smb/profile.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class LevelRegrouping {
public:
    /// Regroups the ordered `boxes` level by level on `threads` threads, cutting again the groups
    /// that left their band; adds each level's seconds to `profile` where `timed`, and returns
    /// the seconds spent cutting. id_at(position) gives a box's id (oversized boxes' tie-break).
    /// `ranges` is room the caller lends for the run: each entry's segments, level by level.
    template <class IdAt>
    double run(std::span<const Box<Real, Dim>> boxes, CutTree<Real, Dim>& cuts, int threads, IdAt&& id_at, bool timed,
               DetectProfile& profile, BulkVector<std::uint32_t>& ranges) {
        const std::size_t n = boxes.size();
        threads_ = threads;
        workers_.resize(threads);
        resize_for_overwrite(oversized_, n);
        std::fill(oversized_.begin(), oversized_.end(), std::uint8_t{0});
        oversized_list_.clear();
        timed_ = timed;
        Stopwatch phase{timed};
        double cutting = regroup_first_level(n, cuts, boxes, ranges, lists_[0], begin_[0]);
        locator_.judge_hints(0, cuts.segments(0), workers_);
        profile.level_seconds[0] += phase.lap();
        cells_list_ = 0;
        cells_begin_ = 0;
        for (int level = 1; level < Dim; ++level) {
            const int source = (level - 1) % 2;
            const int target = level % 2;
            if (columns_ && level == Dim - 1) {
                keep_columns_whole(cuts, begin_[source], begin_[target]);
                cells_list_ = source;
                cells_begin_ = target;
                profile.level_seconds[static_cast<std::size_t>(level)] += phase.lap();
                continue;
            }
            cutting += regroup_level(level, cuts, lists_[source], begin_[source], boxes, ranges, lists_[target],
                                     begin_[target]);
            locator_.judge_hints(level, cuts.segments(level), workers_);
            cells_list_ = target;
            cells_begin_ = target;
            profile.level_seconds[static_cast<std::size_t>(level)] += phase.lap();
        }
        // In x order (ties by id), so that the report and the next order depend on the boxes alone.
        std::sort(oversized_list_.begin(), oversized_list_.end(), [&](Position x, Position y) {
            if (boxes[x].min[0] != boxes[y].min[0]) return boxes[x].min[0] < boxes[y].min[0];
            return id_at(x) < id_at(y);
        });
        return cutting;
    }

    /// Whether the deepest level (x) is left uncut, so that each cell is a whole column of the
    /// level above, checked by a sweep on x (cell_pairs.hpp); else x is cut like every axis.
    void set_columns(bool columns) noexcept { columns_ = columns; }

    /// Every level locates without the hint, or every level tries it again (a cold detection).
    void set_without_hint(bool without) noexcept { locator_.set_without_hint(without); }
    /// The share of the first level's entries whose segment the hint missed in the last run().
    [[nodiscard]] double first_level_misses() const noexcept { return locator_.miss_share(0); }

    /// The cells the last run() built, bounded by `cuts`.
    [[nodiscard]] Cells<Real, Dim> cells(const CutTree<Real, Dim>& cuts) const noexcept {
        return Cells<Real, Dim>{&cuts, lists_[cells_list_], begin_[cells_begin_],
                                columns_ ? std::span<const Real>(widest_) : std::span<const Real>()};
    }

    /// Columns only: where the check of the cells writes each cell's entries back in x order,
    /// and its bound on their x extent (Cells::widest). Empty where x is cut.
    [[nodiscard]] SweptColumns<Real> swept_columns() noexcept {
        if (!columns_) return {};
        widest_.resize(begin_[cells_begin_].size() - 1);
        return {lists_[cells_list_], widest_};
    }

    /// Room between two runs, for a pipeline whose cells nobody reads between detections (the
    /// cells' entries may be in it): the next run() writes it over.
    [[nodiscard]] BulkVector<Position>& spare_list() noexcept { return lists_[0]; }

    /// The oversized boxes of the last run(), in x order (ties by id); they are in no cell.
    [[nodiscard]] std::span<const Position> oversized() const noexcept { return oversized_list_; }
    /// Per position: whether the box is oversized.
    [[nodiscard]] std::span<const std::uint8_t> oversized_flags() const noexcept { return oversized_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = 0;
        for (const auto& list : lists_) bytes += list.capacity() * sizeof(Position);
        for (const auto& begin : begin_) bytes += begin.capacity() * sizeof(std::uint32_t);
        bytes += oversized_.capacity() + oversized_list_.capacity() * sizeof(Position);
        bytes += counts_.capacity() * sizeof(std::uint32_t) + widest_.capacity() * sizeof(Real);
        return bytes + workers_.bytes_held([](const Worker& worker) { return worker.bytes_held(); });
    }

private:
    using Worker = LevelWorker<Real>;
    static constexpr int axis_of_level(int level) noexcept { return CutTree<Real, Dim>::axis_of_level(level); }

    double regroup_first_level(std::size_t n, CutTree<Real, Dim>& cuts, std::span<const Box<Real, Dim>> boxes,
                               BulkVector<std::uint32_t>& ranges, BulkVector<Position>& out,
                               std::vector<std::uint32_t>& out_begin);
    double regroup_level(int level, CutTree<Real, Dim>& cuts, std::span<const Position> in,
                         std::span<const std::uint32_t> in_begin, std::span<const Box<Real, Dim>> boxes,
                         BulkVector<std::uint32_t>& ranges, BulkVector<Position>& out,
                         std::vector<std::uint32_t>& out_begin);
    void publish_marks();
    void keep_columns_whole(CutTree<Real, Dim>& cuts, std::span<const std::uint32_t> in_begin,
                            std::vector<std::uint32_t>& out_begin);

    std::array<BulkVector<Position>, 2> lists_;        // entries of a level, grouped by segment
    std::array<std::vector<std::uint32_t>, 2> begin_;  // group offsets into lists_
    int cells_list_ = 0;                               // which of lists_ holds the cells' entries
    int cells_begin_ = 0;                              // which of begin_ holds their offsets
    std::vector<std::uint32_t> counts_;                // the index array of levels 1 and deeper
    BulkVector<std::uint8_t> oversized_;               // per position; written through atomic_ref
    std::vector<Position> oversized_list_;
    GroupLocator<Real, Dim> locator_;
    PerThread<Worker> workers_;
    int threads_ = 1;
    bool timed_ = true;  // whether the cuts are timed (DetectionSettings::profile)
    bool columns_ = false;
    std::vector<Real> widest_;  // columns: per cell, Cells::widest
};

/// The deepest level of columns: every group whole, no box located. The entries of the level
/// above are the cells' where they are, in each group's first segment, the others empty; the
/// other list, which holds the level before, keeps its own size, not the cells'.
template <std::floating_point Real, int Dim>
void LevelRegrouping<Real, Dim>::keep_columns_whole(CutTree<Real, Dim>& cuts, std::span<const std::uint32_t> in_begin,
                                                    std::vector<std::uint32_t>& out_begin) {
    const std::size_t groups = cuts.groups(Dim - 1);
    const std::uint32_t k = cuts.segments(Dim - 1);
    SMB_ASSERT(in_begin.size() == groups + 1, "one offset per group");
    out_begin.resize(groups * k + 1);
    for (std::size_t g = 0; g < groups; ++g) {
        cuts.leave_whole(Dim - 1, g);
        out_begin[g * k] = in_begin[g];
        std::fill(out_begin.begin() + static_cast<std::ptrdiff_t>(g * k + 1),
                  out_begin.begin() + static_cast<std::ptrdiff_t>((g + 1) * k), in_begin[g + 1]);
    }
    out_begin[groups * k] = in_begin[groups];
}

/// Makes the threads' marks visible as oversized boxes, each once.
template <std::floating_point Real, int Dim>
void LevelRegrouping<Real, Dim>::publish_marks() {
    for (Worker& worker : workers_) {
        for (const Position position : worker.marks) {
            if (oversized_[position] == kPublishedOversized) continue;  // marked in two groups: listed once
            oversized_[position] = kPublishedOversized;
            oversized_list_.push_back(position);
        }
        worker.marks.clear();
    }
}

/// Level 0: one group (all boxes), so the threads share its entries instead of its groups: each
/// locates and counts its share, the index array is summed, and each scatters its share to the
/// offsets that keep the counting sort stable.
template <std::floating_point Real, int Dim>
double LevelRegrouping<Real, Dim>::regroup_first_level(std::size_t n, CutTree<Real, Dim>& cuts,
                                                       std::span<const Box<Real, Dim>> boxes,
                                                       BulkVector<std::uint32_t>& ranges, BulkVector<Position>& out,
                                                       std::vector<std::uint32_t>& out_begin) {
    const std::uint32_t k = cuts.segments(0);
    const auto shares = static_cast<std::size_t>(threads_);
    resize_for_overwrite(ranges, n);  // per entry: first | last segment << 16
    auto share_begin = [&](std::size_t t) { return n * t / shares; };
    auto locate_shares = [&]() {
        std::uint32_t fullest = 0;
#pragma omp parallel for num_threads(threads_) schedule(static, 1)
        for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
            Worker& worker = workers_[static_cast<std::size_t>(t)];
            worker.count.resize(k);
            worker.marks.clear();
            const std::size_t first = share_begin(static_cast<std::size_t>(t));
            const std::size_t last = share_begin(static_cast<std::size_t>(t) + 1);
            const PositionRange share{static_cast<Position>(first), static_cast<Position>(last - first)};
            locator_.locate(0, 0, cuts, share, boxes, ranges.data() + first, worker.count.data(), worker,
                            oversized_.data());
        }
        for (std::uint32_t s = 0; s < k; ++s) {
            std::uint32_t total = 0;
            for (const Worker& worker : workers_) total += worker.count[s];
            fullest = std::max(fullest, total);
        }
        return fullest;
    };
    double cutting = 0;
    const std::uint32_t fullest = cuts.was_cut(0, 0) ? locate_shares() : 0;
    if (cuts.needs_cut(0, 0, fullest)) {
        const Stopwatch cut_watch{timed_};
        cuts.cut_group(
            0, 0, n, [&](std::size_t i) { return boxes[i].min[axis_of_level(0)]; },
            [&](std::size_t i) { return boxes[i].max[axis_of_level(0)] - boxes[i].min[axis_of_level(0)]; },
            workers_[0].quantiles);
        const std::uint32_t balanced = locate_shares();
        std::size_t registrations = 0;
        for (const Worker& worker : workers_)
            for (std::uint32_t s = 0; s < k; ++s) registrations += worker.count[s];
        cuts.set_band(0, 0, registrations, balanced);
        cutting = cut_watch.seconds();
    }
    publish_marks();
    // Offsets: segment by segment, share by share, so that every share keeps its order.
    out_begin.resize(k + 1);
    std::uint32_t offset = 0;
    for (std::uint32_t s = 0; s < k; ++s) {
        out_begin[s] = offset;
        for (Worker& worker : workers_) {
            const std::uint32_t here = worker.count[s];
            worker.count[s] = offset;
            offset += here;
        }
    }
    out_begin[k] = offset;
    resize_for_overwrite(out, offset);
    Position* target = out.data();
    const std::uint32_t* entry_ranges = ranges.data();
#pragma omp parallel for num_threads(threads_) schedule(static, 1)
    for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
        std::uint32_t* cursor = workers_[static_cast<std::size_t>(t)].count.data();
        for (std::size_t i = share_begin(static_cast<std::size_t>(t)); i < share_begin(static_cast<std::size_t>(t) + 1);
             ++i) {
            const std::uint32_t range = entry_ranges[i];
            const std::uint32_t lo = SegmentRange::lo_of(range);
            const std::uint32_t hi = SegmentRange::hi_of(range);
            if (lo > hi) continue;
            target[cursor[lo]++] = static_cast<Position>(i);
            if (hi != lo) target[cursor[hi]++] = static_cast<Position>(i);
        }
    }
    return cutting;
}

/// Levels 1 and deeper: locate and count group by group (cutting again a group that left its
/// band), the groups shared among the threads; then register every box that is not oversized
/// in each segment it touches, by a stable counting sort. Returns the seconds spent cutting:
/// the threads' cutting seconds over the number of threads, a share of the level's wall time
/// (their sum, on several threads, could exceed it).
template <std::floating_point Real, int Dim>
double LevelRegrouping<Real, Dim>::regroup_level(int level, CutTree<Real, Dim>& cuts, std::span<const Position> in,
                                                 std::span<const std::uint32_t> in_begin,
                                                 std::span<const Box<Real, Dim>> boxes,
                                                 BulkVector<std::uint32_t>& ranges, BulkVector<Position>& out,
                                                 std::vector<std::uint32_t>& out_begin) {
    const std::size_t groups = cuts.groups(level);
    const std::uint32_t k = cuts.segments(level);
    const int axis = axis_of_level(level);
    SMB_ASSERT(in_begin.size() == groups + 1, "one offset per group");
    resize_for_overwrite(ranges, in.size());
    // The index array: registrations per segment (shifted by one), turned into offsets below.
    counts_.resize(groups * k + 1);
    std::uint32_t* count = counts_.data();
    count[0] = 0;
    for (Worker& worker : workers_) {
        worker.marks.clear();
        worker.late = false;
    }
    double cutting = 0;
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) reduction(+ : cutting)
    for (std::ptrdiff_t group = 0; group < static_cast<std::ptrdiff_t>(groups); ++group) {
        const auto g = static_cast<std::size_t>(group);
        Worker& worker = workers_.mine();
        const std::span<const Position> entries = in.subspan(in_begin[g], in_begin[g + 1] - in_begin[g]);
        std::uint32_t* group_ranges = ranges.data() + in_begin[g];
        std::uint32_t* segment_count = count + g * k + 1;
        const std::size_t marked_before = worker.marks.size();
        const std::uint32_t fullest = cuts.was_cut(level, g)
                                          ? locator_.locate(level, g, cuts, entries, boxes, group_ranges, segment_count,
                                                            worker, oversized_.data())
                                          : 0;
        if (cuts.needs_cut(level, g, fullest)) {
            const Stopwatch cut_watch{timed_};
            // What the old planes called oversized is judged again against the new ones.
            worker.marks.resize(marked_before);
            // No entry is published oversized (see GroupLocator::locate()): every one takes part.
            cuts.cut_group(
                level, g, entries.size(), [&](std::size_t i) { return boxes[entries[i]].min[axis]; },
                [&](std::size_t i) { return boxes[entries[i]].max[axis] - boxes[entries[i]].min[axis]; },
                worker.quantiles);
            const std::uint32_t balanced =
                locator_.locate(level, g, cuts, entries, boxes, group_ranges, segment_count, worker, oversized_.data());
            std::size_t registrations = 0;
            for (std::uint32_t s = 0; s < k; ++s) registrations += segment_count[s];
            cuts.set_band(level, g, registrations, balanced);
            cutting += cut_watch.seconds();
        }
        for (std::size_t i = marked_before; i < worker.marks.size(); ++i)
            std::atomic_ref<std::uint8_t>(oversized_[worker.marks[i]])
                .store(kMarkedOversized, std::memory_order_relaxed);
    }
    bool late = false;
    for (const Worker& worker : workers_) late = late || worker.late;
    publish_marks();
    if (late) {
        // A box found oversized in one group was counted in the groups before it: count again
        // without it (rare: only boxes much larger than their neighbours' cells).
        std::fill(count, count + groups * k + 1, 0U);
        for (std::size_t g = 0; g < groups; ++g) {
            std::uint32_t* segment_count = count + g * k + 1;
            for (std::uint32_t i = in_begin[g]; i < in_begin[g + 1]; ++i) {
                if (oversized_[in[i]]) ranges[i] = SegmentRange::kNone;
                const std::uint32_t range = ranges[i];
                for (std::uint32_t s = SegmentRange::lo_of(range); s <= SegmentRange::hi_of(range); ++s)
                    ++segment_count[s];
            }
        }
    }
    for (std::size_t s = 0; s < groups * k; ++s) count[s + 1] += count[s];
    out_begin.assign(count, count + groups * k + 1);
    resize_for_overwrite(out, out_begin.back());
    // The stack pass: each entry goes to the next free place of its segments, keeping the order
    // the entries came in (last step's), which keeps each cell's boxes in a few runs of the
    // ordered array, and a swept cell almost sorted.
    Position* target = out.data();
    const std::uint32_t* entry_ranges = ranges.data();
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 4)
    for (std::ptrdiff_t group = 0; group < static_cast<std::ptrdiff_t>(groups); ++group) {
        const auto g = static_cast<std::size_t>(group);
        std::uint32_t* cursor = count + g * k;
        for (std::uint32_t i = in_begin[g]; i < in_begin[g + 1]; ++i) {
            const std::uint32_t range = entry_ranges[i];
            const std::uint32_t lo = SegmentRange::lo_of(range);
            const std::uint32_t hi = SegmentRange::hi_of(range);
            if (lo > hi) continue;
            target[cursor[lo]++] = in[i];
            if (hi != lo) target[cursor[hi]++] = in[i];
        }
    }
    return cutting / threads_;
}

}  // namespace smb::detail
