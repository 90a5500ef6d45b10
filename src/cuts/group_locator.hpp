// SPDX-License-Identifier: MIT
#pragma once
// Where each entry of a group of one level falls: the segments of the group that a box's
// [min, max] touches on the level's axis, against the group's planes (cut_tree.hpp), and how many
// boxes each segment registers: the index array of the singular regrouping (level_regrouping.hpp).
// Most boxes stay in last step's segment, so the previous entry's segment is tried first (the
// hint), unless the last detection showed that the hint misses too often on this level.

#include <algorithm>
#include <array>
#include <atomic>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/assert.hpp"
#include "core/thread_team.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/quantile_select.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// What a box is, per position, on the levels built so far (written through atomic_ref).
inline constexpr std::uint8_t kMarkedOversized = 1;     // found oversized on the level being built
inline constexpr std::uint8_t kPublishedOversized = 2;  // found oversized on an earlier level

/// Positions first, first + 1, ...: the entries of level 0, which reads the ordered boxes in
/// order (a std::views::iota would do, but clang 14 cannot compile libstdc++ 12's).
struct PositionRange {
    Position first;
    Position count;
    [[nodiscard]] std::size_t size() const noexcept { return count; }
    Position operator[](std::size_t i) const noexcept { return first + static_cast<Position>(i); }
};

/// What one thread needs for itself while the groups of a level are located and cut.
template <std::floating_point Real>
struct LevelWorker {
    QuantileSelector<Real> quantiles;  // a group's lower ends and the buffers of its axial cut
    std::vector<Position> marks;       // boxes this thread found oversized on this level
    std::vector<std::uint32_t> count;  // level 0: this thread's share of the index array
    bool late = false;                 // marked a box some earlier group may have counted
    std::size_t located = 0;           // entries located on this level
    std::size_t hint_misses = 0;       // ... whose min lay neither in the hint's segment nor the next

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return quantiles.bytes_held() + marks.capacity() * sizeof(Position) + count.capacity() * sizeof(std::uint32_t);
    }
};

template <std::floating_point Real, int Dim>
class GroupLocator {
public:
    using Worker = LevelWorker<Real>;

    /// Locates every entry of one group against the group's planes and counts its registrations
    /// per segment into `count` (k counters). A box spanning more than two segments is noted in
    /// worker.marks (published as oversized once the group's planes are final) and not counted.
    /// Returns the fullest segment's count. `oversized` is read by the invariant checks only.
    template <class Entries>
    std::uint32_t locate(int level, std::size_t group, const CutTree<Real, Dim>& cuts, const Entries& entries,
                         std::span<const Box<Real, Dim>> boxes, std::uint32_t* ranges, std::uint32_t* count,
                         Worker& worker, [[maybe_unused]] std::uint8_t* oversized) const;

    /// Whether the next detection locates the entries of `level` without the hint, from the misses
    /// the workers counted on it (and reset). The hint saves a search where entries follow last
    /// step's cells, and costs a mispredicted branch besides the search where they do not (boxes
    /// that cross cells every step, as at Λ = 0.1, or all jumped at once). Only time depends on it.
    void judge_hints(int level, std::uint32_t segments, PerThread<Worker>& workers) {
        std::size_t located = 0;
        std::size_t misses = 0;
        for (Worker& worker : workers) {
            located += worker.located;
            misses += worker.hint_misses;
            worker.located = 0;
            worker.hint_misses = 0;
        }
        // Break-even, from the costs of a hit, a mispredicted miss and a search: about one miss in
        // four against a count of at most 64 planes (segment_of), one in two against a binary search.
        const std::size_t share = segments <= 65 ? 4 : 2;
        if (located > 0) without_hint_[level] = share * misses > located;
        miss_share_[level] = located > 0 ? static_cast<double>(misses) / static_cast<double>(located) : 0.0;
    }

    /// The share of the entries of `level` whose min the hint missed, in the last judgement.
    [[nodiscard]] double miss_share(int level) const noexcept { return miss_share_[level]; }

    /// Every level locates without the hint, or every level tries it again (a cold detection,
    /// whose entries come column by column).
    void set_without_hint(bool without) noexcept { without_hint_.fill(without); }

private:
    std::array<bool, Dim> without_hint_{};  // per level, judge_hints()
    std::array<double, Dim> miss_share_{};  // per level, judge_hints()
};

template <std::floating_point Real, int Dim>
template <class Entries>
std::uint32_t GroupLocator<Real, Dim>::locate(int level, std::size_t group, const CutTree<Real, Dim>& cuts,
                                              const Entries& entries, std::span<const Box<Real, Dim>> boxes,
                                              std::uint32_t* ranges, std::uint32_t* count, Worker& worker,
                                              [[maybe_unused]] std::uint8_t* oversized) const {
    const int axis = CutTree<Real, Dim>::axis_of_level(level);
    const std::span<const Real> planes = cuts.cuts(level, group);
    const std::uint32_t k = cuts.segments(level);
    std::fill(count, count + k, 0U);
    std::size_t misses = 0;
    // One loop per way of locating the min, so that the hinted one is as tight as without the choice.
    auto locate_all = [&](auto hinted) {
        std::uint32_t lo = 0;
        // Where the hint holds, the entries come in last step's segment order, so the mins fall
        // in long runs of one segment: counted in registers, a run reaches `count` once, where
        // counting each entry in memory chained every entry to the previous one's store. Without
        // the hint (boxes that jump segments) runs are short, and the branch that ends one would
        // guess wrong: each entry is counted in memory there.
        std::uint32_t run = 0;
        std::uint32_t run_mins = 0;
        std::uint32_t run_crossings = 0;  // boxes of the run whose max lies in segment run + 1
        auto end_run = [&]() {
            count[run] += run_mins;
            if (run_crossings != 0) count[run + 1] += run_crossings;
        };
        [[maybe_unused]] constexpr std::size_t ahead = 16;
        // A copy: held by reference, the entries' pointer was read again at every entry (the
        // rare push_back below may, for all the compiler knows, change it).
        const Entries listed = entries;
        for (std::size_t i = 0; i < listed.size(); ++i) {
            // Where boxes jumped since the last step, the entries of levels 1 and deeper point
            // anywhere in the box array; level 0 reads it in order.
            if constexpr (!std::is_same_v<Entries, PositionRange>) {
                if (i + ahead < listed.size()) __builtin_prefetch(&boxes[listed[i + ahead]]);
            }
            const Position position = listed[i];
#ifdef SMB_VALIDATE
            // The levels before registered no box they published as oversized (their count is
            // redone without a box marked late), so no entry needs that test. A mark another
            // thread makes on this level meanwhile (1) is not published yet.
            SMB_ASSERT(std::atomic_ref<std::uint8_t>(oversized[position]).load(std::memory_order_relaxed) !=
                           kPublishedOversized,
                       "an entry was published as oversized on an earlier level");
#endif
            const Box<Real, Dim>& box = boxes[position];
            if constexpr (decltype(hinted)::value) {
                lo = segment_near(planes, box.min[axis], lo, misses);
            } else {
                const std::uint32_t found = segment_of(planes, box.min[axis]);
                // What segment_near would have counted: found outside lo - 1 .. lo + 1 (wraps round below).
                misses += found - lo + 1 > 2 ? 1U : 0U;
                lo = found;
            }
            const std::uint32_t hi = segment_of_max(planes, box.max[axis], lo);
            if (hi - lo > 1) {
                worker.marks.push_back(position);
                // Counted already if it was registered in an earlier group of this level.
                worker.late = worker.late || level > 0;
                ranges[i] = SegmentRange::kNone;
                continue;
            }
            ranges[i] = lo | (hi << 16);
            if constexpr (decltype(hinted)::value) {
                if (lo != run) {
                    end_run();
                    run = lo;
                    run_mins = 0;
                    run_crossings = 0;
                }
                ++run_mins;
                run_crossings += hi - lo;
            } else {
                ++count[lo];
                count[hi] += hi != lo ? 1U : 0U;
            }
        }
        end_run();
    };
    if (without_hint_[level]) {
        locate_all(std::false_type{});
    } else {
        locate_all(std::true_type{});
    }
    worker.located += entries.size();
    worker.hint_misses += misses;
    return *std::max_element(count, count + k);
}

}  // namespace smb::detail
