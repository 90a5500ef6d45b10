#pragma once
// The default pipeline: SMB's levels of axial cuts, with the cuts kept from one step to the next
// (cut_tree.hpp) so that every level is a linear bucketing pass instead of a sort.
//
// Per detection:
//   1. order_ holds every box once, in last step's cell order (x-sorted within a swept cell).
//   2. Level l (axis Dim-1-l): every box of every group is located against the group's planes
//      (segment_of) and registered, by a stable counting sort (the singular regrouping: index
//      array of counts, then a stack of offsets), in each segment its [min, max] touches. A group
//      whose fullest segment left its band is cut again first (the axial cut). A box that spans
//      more than two segments is oversized: it leaves the levels and is checked apart.
//   3. Each cell of the deepest level is checked by cell_pairs.hpp (every pair, or a sweep for
//      a crowded cell), which also writes the next order_.
//   4. Oversized boxes are tested against the cells they cover and against one another.
// docs/algorithm.md gives the proof that each overlapping pair is reported exactly once.

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <concepts>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "core/assert.hpp"
#include "core/id_index.hpp"
#include "cuts/cell_pairs.hpp"
#include "cuts/cut_tree.hpp"
#include "core/growth.hpp"
#include "core/held_box.hpp"
#include "core/ordered_rounds.hpp"
#include "core/pair_output.hpp"
#include "core/prefetch.hpp"
#include "core/slot_renumbering.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace smb::detail {

template <std::floating_point Real, int Dim, std::floating_point Input = Real>
class PersistentCutPipeline {
public:
    /// Drops removed slots from the order and renumbers the others (BoxStore::compact(), which
    /// leaves the listed boxes in the first slots).
    void fold_removals(const SlotRenumbering& renumbering) {
        std::size_t write = 0;
        for (const Slot slot : order_) {
            const Slot now = renumbering(slot);
            if (now != kNoSlot) order_[write++] = now;
        }
        order_.resize(write);
        listed_ = write;
    }

    /// Slots [0, listed()) are in the order; later ones arrived since the last detection.
    [[nodiscard]] std::size_t listed() const noexcept { return listed_; }

    /// Forgets the slots from `n` on: a Detector's caller passed fewer boxes than last time.
    void forget_slots_from(std::size_t n) {
        if (n >= listed_) return;
        std::erase_if(order_, [n](Slot slot) { return slot >= n; });
        listed_ = std::min(listed_, n);
    }

    /// Reports every overlapping pair of `input` once (report.append(pairs in a < b order) for
    /// runs, report(id_a, id_b) for single pairs): box `slot` of `input` under id ids[slot], or
    /// under id `slot` where `ids` is empty. Where the pipeline holds floats of double input, the held
    /// boxes are shifted by set_origin()'s origin and rounded (held_box.hpp), and each pair they
    /// cannot settle is tested again on `input`.
    template <class Report>
    void detect(std::span<const Box<Input, Dim>> input, std::span<const BoxId> ids, const WorldSettings& settings,
                Report& report, DetectStats& stats);

    /// The order the last detection left: every slot once, cell by cell.
    [[nodiscard]] std::span<const Slot> order() const noexcept { return order_; }

    /// Where held coordinates start from (rounded input only); a new origin forgets every plane.
    void set_origin(const std::array<Input, Dim>& origin) {
        origin_ = origin;
        cuts_.forget();
        order_state_ = OrderState::fresh;
    }

    /// The bounds of the boxes the next detection gets (rounded input only): held boxes that
    /// overlap by held_sure_margin() on every axis then need no second test on the input.
    void set_scene_bounds(const std::array<Input, Dim>& lo, const std::array<Input, Dim>& hi) {
        if constexpr (kRounded) sure_margin_ = held_sure_margin<Input, Dim>(origin_, lo, hi);
    }

    /// Calls visit(slot) once for every box of the last detection whose held box overlaps `query`
    /// (closed), through the cells that `query` covers and the oversized boxes; valid until the
    /// next detection or change. The skin list (skin_list.hpp) finds the neighbours of a box that
    /// left its skin this way, without a detection of its own.
    template <class Visit>
    void for_each_held_overlapping(const Box<Real, Dim>& query, Visit&& visit) const;

    /// Pairs that the held floats could not settle, tested again on the input, in the last
    /// detection (rounded input only).
    [[nodiscard]] std::size_t retested() const noexcept { return retested_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = (order_.capacity() + next_order_.capacity()) * sizeof(Slot);
        bytes += ordered_.capacity() * sizeof(Box<Real, Dim>) + ordered_ids_.capacity() * sizeof(BoxId);
        for (const auto& list : lists_) bytes += list.capacity() * sizeof(Slot);
        for (const auto& begin : begin_) bytes += begin.capacity() * sizeof(std::uint32_t);
        bytes += ranges_.capacity() * sizeof(std::uint32_t);
        bytes += oversized_.capacity() + oversized_list_.capacity() * sizeof(Position);
        bytes += counts_.capacity() * sizeof(std::uint32_t);
        bytes += workers_.capacity() * sizeof(WorkerScratch) + blocks_.capacity() * sizeof(BlockOutput);
        for (const WorkerScratch& worker : workers_) {
            bytes += worker.quantiles.bytes_held() + worker.marks.capacity() * sizeof(Position) +
                     worker.count.capacity() * sizeof(std::uint32_t) + worker.sweep.bytes_held();
        }
        for (const BlockOutput& block : blocks_)
            bytes += block.pairs.capacity() * sizeof(Pair) + block.home.capacity() * sizeof(Position);
        return bytes + cuts_.bytes_held();
    }

private:
    using Clock = std::chrono::steady_clock;
    static constexpr int axis_of_level(int level) noexcept { return Dim - 1 - level; }
    static constexpr std::uint32_t lo_of(std::uint32_t range) noexcept { return range & 0xFFFFU; }
    static constexpr std::uint32_t hi_of(std::uint32_t range) noexcept { return range >> 16; }
    static constexpr std::uint32_t kNoRange = 1;  // first segment 1, last 0: registered nowhere
    static constexpr std::uint8_t kMarked = 1;     // found oversized on the level being built
    static constexpr std::uint8_t kPublished = 2;  // found oversized on an earlier level

    /// Entries of the levels and cells are positions in order_ (and in ordered_), not slots.
    using Position = std::uint32_t;

    /// Positions first, first + 1, ...: the entries of level 0, which reads the ordered boxes in
    /// order (a std::views::iota would do, but clang 14 cannot compile libstdc++ 12's).
    struct PositionRange {
        Position first;
        Position count;
        [[nodiscard]] std::size_t size() const noexcept { return count; }
        Position operator[](std::size_t i) const noexcept { return first + static_cast<Position>(i); }
    };

    /// What one thread needs for itself while groups or cells are shared out.
    struct alignas(64) WorkerScratch {
        QuantileSelector<Real> quantiles;  // a group's lower ends and the buffers of its axial cut
        std::vector<Position> marks;       // boxes this thread found oversized on this level
        std::vector<std::uint32_t> count;  // level 0: this thread's share of the index array
        CellPairs<Real, Dim> sweep;
        bool late = false;                 // marked a box some earlier group may have counted
        std::size_t located = 0;           // entries located on this level
        std::size_t hint_misses = 0;       // ... whose min lay neither in the hint's segment nor the next
    };
    /// The pairs and home boxes of one block of cells (a column), handed on in block order so
    /// that the report is the same whatever the number of threads.
    struct alignas(64) BlockOutput {
        std::vector<Pair> pairs;  // its first `filled` hold this block's pairs
        std::size_t filled = 0;
        std::vector<Position> home;
        std::size_t moves = 0;
        bool overflowed = false;
    };

    void plan_segments(std::size_t n, const WorldSettings& settings);
    void plan_threads(const WorldSettings& settings);
    double run_levels(std::span<const Box<Input, Dim>> store_boxes, std::span<const BoxId> store_ids,
                      DetectStats& stats);
    void gather_in_order(std::span<const Box<Input, Dim>> store_boxes, std::span<const BoxId> store_ids);
    double regroup_level(int level, std::span<const Position> in, std::span<const std::uint32_t> in_begin,
                         std::span<const Box<Real, Dim>> boxes, std::vector<Position>& out,
                         std::vector<std::uint32_t>& out_begin);
    template <class Entries>
    std::uint32_t locate_group(int level, std::size_t group, const Entries& entries,
                               std::span<const Box<Real, Dim>> boxes, std::uint32_t* ranges,
                               std::uint32_t* count, WorkerScratch& worker);
    double regroup_first_level(std::size_t n, std::span<const Box<Real, Dim>> boxes,
                               std::vector<Position>& out, std::vector<std::uint32_t>& out_begin);
    void publish_marks();
    void judge_hints(int level);
    template <class Report>
    std::size_t check_cells(std::span<const Box<Real, Dim>> boxes, Report& report);
    template <class Report, class Work>
    std::size_t in_ordered_rounds(std::size_t count, Report& report, std::vector<Position>& home, Work&& work);
    template <class Collect>
    std::size_t check_column(std::size_t column, std::span<const Box<Real, Dim>> boxes, CellPairs<Real, Dim>& sweep,
                             Collect& collect, std::vector<Position>& home, const bool* give_up);
    /// Pairs one column may hold while the threads check a round (4 MiB); see check_cells().
    static constexpr std::size_t kBlockPairCap = std::size_t{1} << 18;
    template <class Report>
    void check_oversized(std::span<const Box<Real, Dim>> boxes, Report& report);
    template <class Collect>
    void check_one_oversized(std::size_t index, std::span<const Box<Real, Dim>> boxes, Collect& collect,
                             const bool* give_up) const;
    template <class Visit>
    void for_each_cell_covering(const Box<Real, Dim>& box, Visit&& visit) const;
    template <class Visit>
    void for_each_cell_box_overlapping(const Box<Real, Dim>& query, std::span<const Box<Real, Dim>> boxes,
                                       Visit&& visit, const bool* give_up = nullptr) const;
    CellFloor<Real, Dim> floor_of_cell(std::size_t cell) const;
    void check_invariants(std::span<const Box<Real, Dim>> boxes) const;

    /// Held boxes at positions a and b overlap: true when their input boxes do too. `sure`:
    /// the cell check found them overlapping by the sure margin (set_scene_bounds()).
    [[nodiscard]] bool confirmed(Position a, Position b, bool sure = false) {
        if constexpr (kRounded) {
            if (sure || surely_overlap(ordered_[a], ordered_[b])) return true;
            // Counted per thread would be exact too; a relaxed atomic is simpler and rare.
            std::atomic_ref<std::size_t>(retested_).fetch_add(1, std::memory_order_relaxed);
            // The input is indexed by slot, which order_ still gives while a detection runs.
            return overlaps(input_[order_[a]], input_[order_[b]]);
        } else {
            (void)a;
            (void)b;
            (void)sure;
            return true;
        }
    }

    /// Floats held for double input: every pair the floats pass is confirmed on the input.
    static constexpr bool kRounded = !std::same_as<Real, Input>;
    static_assert(!kRounded || std::same_as<Real, float>, "rounded input is held as floats");

    std::span<const Box<Input, Dim>> input_;  // the boxes of the detection under way
    std::array<Input, Dim> origin_{};
    float sure_margin_ = std::numeric_limits<float>::infinity();  // infinity: proves nothing
    std::size_t retested_ = 0;
    std::vector<Slot> order_;       // every slot once: last step's cells, x-sorted within swept ones
    std::vector<Position> next_order_;   // positions of the home boxes, cell by cell
    std::vector<Box<Real, Dim>> ordered_;   // the boxes in order_'s order, copied each step
    std::vector<BoxId> ordered_ids_;        // and their ids, unless the ids are the slots
    bool own_ids_ = true;                   // ids were given; else box `slot` has id `slot`

    /// The id of the box at `position`: while a detection runs, order_ still maps positions to
    /// slots, so slot ids need no array of their own (8 bytes a box less for a Detector).
    [[nodiscard]] BoxId id_at(Position position) const noexcept {
        return own_ids_ ? ordered_ids_[position] : BoxId{order_[position]};
    }
    std::size_t listed_ = 0;        // slots [0, listed_) are in order_; later ones are new
    CutTree<Real, Dim> cuts_;
    std::array<std::vector<Slot>, 2> lists_;             // entries of a level, grouped by segment
    std::array<std::vector<std::uint32_t>, 2> begin_;    // group offsets into lists_
    int cells_list_ = 0;                                 // which of lists_ holds the cells
    std::vector<std::uint32_t> ranges_;  // per entry of the level: first | last segment << 16
    std::vector<std::uint32_t> counts_;
    std::vector<std::uint8_t> oversized_;   // per position; written through atomic_ref
    std::vector<Position> oversized_list_;
    int threads_ = 1;
    /// What order_ follows: no cells at all (the first detection, a new origin; the order is
    /// cold, each cell's boxes scattered over the ordered copy), or last step's cells.
    enum class OrderState { fresh, follows_cells };
    OrderState order_state_ = OrderState::fresh;
    // Per level: locate without the hint, which missed for more than a quarter of the entries
    // (half, beyond 64 planes) in the last detection: boxes that move across cells every step,
    // as at Λ = 0.1, or that all jumped at once (judge_hints()).
    std::array<bool, Dim> locate_without_hint_{};
    std::vector<WorkerScratch> workers_;     // one per thread
    std::vector<BlockOutput> blocks_;         // one per block of a round of cell checks
};

/// About (N / target population)^(1/Dim) segments per group, so that cells hold about the target
/// number of boxes; changed only when N has moved by more than a quarter, since a new count
/// forgets every plane.
template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::plan_segments(std::size_t n, const WorldSettings& settings) {
    const double cells = static_cast<double>(n) / static_cast<double>(settings.target_cell_population);
    const double ideal = std::clamp(std::pow(cells, 1.0 / Dim), 1.0, double{CutTree<Real, Dim>::kMaxSegments});
    const double current = cuts_.segments();
    if (current == 0 || ideal > 1.25 * current || ideal < 0.8 * current) {
        cuts_.reshape(static_cast<std::uint32_t>(std::lround(ideal)));
    }
}

template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Report>
void PersistentCutPipeline<Real, Dim, Input>::detect(std::span<const Box<Input, Dim>> store_boxes,
                                                     std::span<const BoxId> store_ids, const WorldSettings& settings,
                                                     Report& report, DetectStats& stats) {
    const std::size_t n = store_boxes.size();
    input_ = store_boxes;
    retested_ = 0;
    reserve_with_slack(order_, n);
    for (std::size_t slot = listed_; slot < n; ++slot) order_.push_back(static_cast<Slot>(slot));
    listed_ = n;
    SMB_ASSERT(order_.size() == n, "the order holds every box once");
    if (n == 0) {
        cuts_.forget();
        return;
    }
    const std::uint32_t segments_before = cuts_.segments();
    plan_segments(n, settings);
    plan_threads(settings);
    // A cold order (first detection, new cut counts) scatters each cell's boxes over the
    // ordered array. The check then reads them out of order, prefetched; renumbering them in
    // cell order first (a second copy of every box) cost more than it saved once cells were
    // checked by testing every pair (docs/performance.md).
    const bool cold = order_state_ == OrderState::fresh || cuts_.segments() != segments_before;
    // In a cold order the previous entry says nothing of the next one's segment. Boxes that
    // jumped far since the last step are left to judge_hints(), which measured the misses.
    if (cold) locate_without_hint_.fill(true);

    const auto start = Clock::now();
    const double cutting = run_levels(store_boxes, store_ids, stats);
    // The misses of a cold order say nothing of the next detection, whose entries will come in
    // this one's cells: it tries the hint, and judges again from its own misses.
    if (cold) locate_without_hint_.fill(false);
    const std::span<const Box<Real, Dim>> boxes(ordered_);
    const double regrouping = std::chrono::duration<double>(Clock::now() - start).count();
    stats.sort_seconds = cutting;
    stats.cut_regroup_seconds = regrouping - cutting;
    stats.cells = cuts_.cells();

    const auto check_start = Clock::now();
    stats.sort_moves = check_cells(boxes, report);
    check_oversized(boxes, report);
    stats.oversized_boxes = oversized_list_.size();
    stats.check_seconds = std::chrono::duration<double>(Clock::now() - check_start).count();
#ifdef SMB_VALIDATE
    check_invariants(boxes);
#endif
    // The check wrote positions in the ordered copy; the next order holds their slots. How far
    // boxes moved in the order is no sign of motion (the boxes a step adds shift every later
    // place by up to their number): judge_hints() measured the misses (docs/performance.md).
    const auto count = static_cast<std::ptrdiff_t>(next_order_.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t i = 0; i < count; ++i) next_order_[i] = order_[next_order_[i]];
    order_.swap(next_order_);
    order_state_ = OrderState::follows_cells;
}

/// Copies the boxes in order_'s order and regroups them level by level; returns the seconds
/// spent cutting, and writes the copy's and each level's seconds to `stats`.
template <std::floating_point Real, int Dim, std::floating_point Input>
double PersistentCutPipeline<Real, Dim, Input>::run_levels(std::span<const Box<Input, Dim>> store_boxes,
                                                   std::span<const BoxId> store_ids, DetectStats& stats) {
    const std::size_t n = store_boxes.size();
    auto seconds_since = [](Clock::time_point start) {
        return std::chrono::duration<double>(Clock::now() - start).count();
    };
    auto phase = Clock::now();
    resize_with_slack(oversized_, n);
    std::fill(oversized_.begin(), oversized_.end(), std::uint8_t{0});
    oversized_list_.clear();
    // The boxes are copied once in last step's cell order: every later pass reads them almost
    // sequentially, where reading them by slot would miss the cache on nearly every box.
    gather_in_order(store_boxes, store_ids);
    stats.copy_seconds = seconds_since(phase);
    phase = Clock::now();
    const std::span<const Box<Real, Dim>> boxes(ordered_);
    double cutting = regroup_first_level(n, boxes, lists_[0], begin_[0]);
    judge_hints(0);
    stats.level_seconds[0] = seconds_since(phase);
    cells_list_ = 0;
    for (int level = 1; level < Dim; ++level) {
        phase = Clock::now();
        const int source = (level - 1) % 2;
        const int target = level % 2;
        cutting += regroup_level(level, lists_[source], begin_[source], boxes, lists_[target], begin_[target]);
        judge_hints(level);
        cells_list_ = target;
        stats.level_seconds[static_cast<std::size_t>(level)] = seconds_since(phase);
    }
    // In x order (ties by id), so that the report and the next order depend on the boxes alone.
    std::sort(oversized_list_.begin(), oversized_list_.end(), [&](Position x, Position y) {
        if (boxes[x].min[0] != boxes[y].min[0]) return boxes[x].min[0] < boxes[y].min[0];
        return id_at(x) < id_at(y);
    });
    return cutting;
}

/// Threads: WorldSettings::threads, 0 for as many as OpenMP offers; one without OpenMP.
template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::plan_threads(const WorldSettings& settings) {
#ifdef _OPENMP
    threads_ = settings.threads == 0 ? omp_get_max_threads() : static_cast<int>(settings.threads);
#else
    (void)settings;
    threads_ = 1;
#endif
    threads_ = std::max(threads_, 1);
    if (workers_.size() != static_cast<std::size_t>(threads_)) workers_.resize(static_cast<std::size_t>(threads_));
}

template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::gather_in_order(std::span<const Box<Input, Dim>> store_boxes,
                                                       std::span<const BoxId> store_ids) {
    const std::size_t n = order_.size();
    resize_with_slack(ordered_, n);
    own_ids_ = !store_ids.empty();
    if (own_ids_) resize_with_slack(ordered_ids_, n);
    else std::vector<BoxId>().swap(ordered_ids_);
    // Each box is a miss of its own (the store is in slot order, not cell order) and the loop
    // does little else, so the requests must start far ahead to keep enough in flight: 64
    // measured 5-7 ms shorter than 16 at 1M boxes (docs/performance.md).
    constexpr std::size_t ahead = 64;
    const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t j = 0; j < count; ++j) {
        const auto i = static_cast<std::size_t>(j);
        if (i + ahead < n) {
            prefetch_whole(&store_boxes[order_[i + ahead]]);
            if (!store_ids.empty()) __builtin_prefetch(&store_ids[order_[i + ahead]]);
        }
        if constexpr (kRounded) {
            ordered_[i] = held_box<Input, Dim>(store_boxes[order_[i]], origin_);
        } else {
            ordered_[i] = store_boxes[order_[i]];
        }
        if (own_ids_) ordered_ids_[i] = store_ids[order_[i]];
    }
}

/// Locates every entry of one group against the group's planes and counts its registrations
/// per segment into `count` (k counters). A box spanning more than two segments is noted in
/// worker.marks (published as oversized once the group's planes are final) and not counted.
/// Returns the fullest segment's count.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Entries>
std::uint32_t PersistentCutPipeline<Real, Dim, Input>::locate_group(int level, std::size_t group,
                                                             const Entries& entries,
                                                             std::span<const Box<Real, Dim>> boxes,
                                                             std::uint32_t* ranges, std::uint32_t* count,
                                                             WorkerScratch& worker) {
    const int axis = axis_of_level(level);
    const std::span<const Real> planes = cuts_.cuts(level, group);
    const std::uint32_t k = cuts_.segments();
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
            // In a cold order (the first detection) the entries of levels 1 and deeper point
            // anywhere in the box array; level 0 reads it in order.
            if constexpr (!std::is_same_v<Entries, PositionRange>) {
                if (i + ahead < listed.size()) __builtin_prefetch(&boxes[listed[i + ahead]]);
            }
            const Position position = listed[i];
#ifdef SMB_VALIDATE
            // The levels before registered no box they published as oversized (their count is
            // redone without a box marked late), so no entry needs that test. A mark another
            // thread makes on this level meanwhile (1) is not published yet.
            SMB_ASSERT(std::atomic_ref<std::uint8_t>(oversized_[position]).load(std::memory_order_relaxed) !=
                           kPublished,
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
                ranges[i] = kNoRange;
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
    if (locate_without_hint_[level]) {
        locate_all(std::false_type{});
    } else {
        locate_all(std::true_type{});
    }
    worker.located += entries.size();
    worker.hint_misses += misses;
    return *std::max_element(count, count + k);
}

/// Whether the next detection locates the entries of `level` without the hint: the hint (the
/// previous entry's segment, or one beside it) saves a search where entries follow last step's
/// cells, and costs a mispredicted branch besides the search where they do not (at 1M boxes in
/// 3D it misses for 0.1% of the entries on the outer levels and 3% on x at Λ = 1e-3, 1.4% and
/// 6% at 1e-2, 60-66% at 0.1).
/// Only time depends on this; the segments are the same either way.
template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::judge_hints(int level) {
    std::size_t located = 0;
    std::size_t misses = 0;
    for (WorkerScratch& worker : workers_) {
        located += worker.located;
        misses += worker.hint_misses;
        worker.located = 0;
        worker.hint_misses = 0;
    }
    // Break-even, from the costs of a hit, a mispredicted miss and a search: about one miss in
    // four against a count of at most 64 planes (segment_of), one in two against a binary search.
    const std::size_t share = cuts_.segments() <= 65 ? 4 : 2;
    if (located > 0) locate_without_hint_[level] = share * misses > located;
}

/// Makes the threads' marks visible as oversized boxes, each once.
template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::publish_marks() {
    for (WorkerScratch& worker : workers_) {
        for (const Position position : worker.marks) {
            if (oversized_[position] == kPublished) continue;  // marked in two groups: listed once
            oversized_[position] = kPublished;
            oversized_list_.push_back(position);
        }
        worker.marks.clear();
    }
}

/// Level 0: one group (all boxes), so the threads share its entries instead of its groups: each
/// locates and counts its share, the index array is summed, and each scatters its share to the
/// offsets that keep the counting sort stable.
template <std::floating_point Real, int Dim, std::floating_point Input>
double PersistentCutPipeline<Real, Dim, Input>::regroup_first_level(std::size_t n,
                                                             std::span<const Box<Real, Dim>> boxes,
                                                             std::vector<Position>& out,
                                                             std::vector<std::uint32_t>& out_begin) {
    const std::uint32_t k = cuts_.segments();
    const auto shares = static_cast<std::size_t>(threads_);
    resize_with_slack(ranges_, n);
    auto share_begin = [&](std::size_t t) { return n * t / shares; };
    auto locate_shares = [&]() {
        std::uint32_t fullest = 0;
#pragma omp parallel for num_threads(threads_) schedule(static, 1)
        for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
            WorkerScratch& worker = workers_[static_cast<std::size_t>(t)];
            worker.count.resize(k);
            worker.marks.clear();
            const std::size_t first = share_begin(static_cast<std::size_t>(t));
            const std::size_t last = share_begin(static_cast<std::size_t>(t) + 1);
            locate_group(0, 0, PositionRange{static_cast<Position>(first), static_cast<Position>(last - first)},
                         boxes, ranges_.data() + first,
                         worker.count.data(), worker);
        }
        for (std::uint32_t s = 0; s < k; ++s) {
            std::uint32_t total = 0;
            for (const WorkerScratch& worker : workers_) total += worker.count[s];
            fullest = std::max(fullest, total);
        }
        return fullest;
    };
    double cutting = 0;
    const std::uint32_t fullest = cuts_.was_cut(0, 0) ? locate_shares() : 0;
    if (cuts_.needs_cut(0, 0, fullest)) {
        const auto cut_start = Clock::now();
        cuts_.cut_group(0, 0, n, [&](std::size_t i) { return boxes[i].min[axis_of_level(0)]; },
                        workers_[0].quantiles);
        const std::uint32_t balanced = locate_shares();
        std::size_t registrations = 0;
        for (const WorkerScratch& worker : workers_)
            for (std::uint32_t s = 0; s < k; ++s) registrations += worker.count[s];
        cuts_.set_band(0, 0, registrations, balanced);
        cutting = std::chrono::duration<double>(Clock::now() - cut_start).count();
    }
    publish_marks();
    // Offsets: segment by segment, share by share, so that every share keeps its order.
    out_begin.resize(k + 1);
    std::uint32_t offset = 0;
    for (std::uint32_t s = 0; s < k; ++s) {
        out_begin[s] = offset;
        for (WorkerScratch& worker : workers_) {
            const std::uint32_t here = worker.count[s];
            worker.count[s] = offset;
            offset += here;
        }
    }
    out_begin[k] = offset;
    resize_with_slack(out, offset);
    Position* target = out.data();
#pragma omp parallel for num_threads(threads_) schedule(static, 1)
    for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
        std::uint32_t* cursor = workers_[static_cast<std::size_t>(t)].count.data();
        for (std::size_t i = share_begin(static_cast<std::size_t>(t)); i < share_begin(static_cast<std::size_t>(t) + 1); ++i) {
            const std::uint32_t range = ranges_[i];
            const std::uint32_t lo = lo_of(range);
            const std::uint32_t hi = hi_of(range);
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
template <std::floating_point Real, int Dim, std::floating_point Input>
double PersistentCutPipeline<Real, Dim, Input>::regroup_level(int level, std::span<const Position> in,
                                                       std::span<const std::uint32_t> in_begin,
                                                       std::span<const Box<Real, Dim>> boxes,
                                                       std::vector<Position>& out,
                                                       std::vector<std::uint32_t>& out_begin) {
    const std::size_t groups = cuts_.groups(level);
    const std::uint32_t k = cuts_.segments();
    const int axis = axis_of_level(level);
    SMB_ASSERT(in_begin.size() == groups + 1, "one offset per group");
    resize_with_slack(ranges_, in.size());
    // The index array: registrations per segment (shifted by one), turned into offsets below.
    counts_.resize(groups * k + 1);
    std::uint32_t* count = counts_.data();
    count[0] = 0;
    for (WorkerScratch& worker : workers_) {
        worker.marks.clear();
        worker.late = false;
    }
    double cutting = 0;
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 1) reduction(+ : cutting)
    for (std::ptrdiff_t group = 0; group < static_cast<std::ptrdiff_t>(groups); ++group) {
        const auto g = static_cast<std::size_t>(group);
        WorkerScratch& worker = workers_[static_cast<std::size_t>(this_thread())];
        const std::span<const Position> entries = in.subspan(in_begin[g], in_begin[g + 1] - in_begin[g]);
        std::uint32_t* ranges = ranges_.data() + in_begin[g];
        std::uint32_t* segment_count = count + g * k + 1;
        const std::size_t marked_before = worker.marks.size();
        const std::uint32_t fullest =
            cuts_.was_cut(level, g) ? locate_group(level, g, entries, boxes, ranges, segment_count, worker) : 0;
        if (cuts_.needs_cut(level, g, fullest)) {
            const auto cut_start = Clock::now();
            // What the old planes called oversized is judged again against the new ones.
            worker.marks.resize(marked_before);
            // No entry is published oversized (see locate_group()): every one takes part.
            cuts_.cut_group(level, g, entries.size(), [&](std::size_t i) { return boxes[entries[i]].min[axis]; },
                            worker.quantiles);
            const std::uint32_t balanced = locate_group(level, g, entries, boxes, ranges, segment_count, worker);
            std::size_t registrations = 0;
            for (std::uint32_t s = 0; s < k; ++s) registrations += segment_count[s];
            cuts_.set_band(level, g, registrations, balanced);
            cutting += std::chrono::duration<double>(Clock::now() - cut_start).count();
        }
        for (std::size_t i = marked_before; i < worker.marks.size(); ++i)
            std::atomic_ref<std::uint8_t>(oversized_[worker.marks[i]]).store(kMarked, std::memory_order_relaxed);
    }
    bool late = false;
    for (const WorkerScratch& worker : workers_) late = late || worker.late;
    publish_marks();
    if (late) {
        // A box found oversized in one group was counted in the groups before it: count again
        // without it (rare: only boxes much larger than their neighbours' cells).
        std::fill(count, count + groups * k + 1, 0U);
        for (std::size_t g = 0; g < groups; ++g) {
            std::uint32_t* segment_count = count + g * k + 1;
            for (std::uint32_t i = in_begin[g]; i < in_begin[g + 1]; ++i) {
                if (oversized_[in[i]]) ranges_[i] = kNoRange;
                const std::uint32_t range = ranges_[i];
                for (std::uint32_t s = lo_of(range); s <= hi_of(range); ++s) ++segment_count[s];
            }
        }
    }
    for (std::size_t s = 0; s < groups * k; ++s) count[s + 1] += count[s];
    out_begin.assign(count, count + groups * k + 1);
    resize_with_slack(out, out_begin.back());
    // The stack pass: each entry goes to the next free place of its segments, keeping the order
    // the entries came in (last step's), which keeps each cell's boxes in a few runs of the
    // ordered array, and a swept cell almost sorted.
    Position* target = out.data();
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 4)
    for (std::ptrdiff_t group = 0; group < static_cast<std::ptrdiff_t>(groups); ++group) {
        const auto g = static_cast<std::size_t>(group);
        std::uint32_t* cursor = count + g * k;
        for (std::uint32_t i = in_begin[g]; i < in_begin[g + 1]; ++i) {
            const std::uint32_t range = ranges_[i];
            const std::uint32_t lo = lo_of(range);
            const std::uint32_t hi = hi_of(range);
            if (lo > hi) continue;
            target[cursor[lo]++] = in[i];
            if (hi != lo) target[cursor[hi]++] = in[i];
        }
    }
    return cutting / threads_;
}

template <std::floating_point Real, int Dim, std::floating_point Input>
CellFloor<Real, Dim> PersistentCutPipeline<Real, Dim, Input>::floor_of_cell(std::size_t cell) const {
    CellFloor<Real, Dim> floor{};
    const std::uint32_t k = cuts_.segments();
    std::size_t group = cell;
    for (int level = Dim - 1; level >= 0; --level) {
        const auto segment = static_cast<std::uint32_t>(group % k);
        group /= k;
        floor[axis_of_level(level)] = cuts_.lower(level, group, segment);
    }
    return floor;
}

/// The cells are checked column by column (a column: the k cells of one group of the deepest
/// level), in column order, so the report does not depend on the thread count.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Report>
std::size_t PersistentCutPipeline<Real, Dim, Input>::check_cells(std::span<const Box<Real, Dim>> boxes,
                                                          Report& report) {
    next_order_.clear();
    reserve_with_slack(next_order_, boxes.size());
    for (WorkerScratch& worker : workers_) worker.sweep.set_sure_margin(sure_margin_);
    const std::size_t moves = in_ordered_rounds(
        cuts_.groups(Dim - 1), report, next_order_,
        [&](std::size_t column, auto& collect, std::vector<Position>& home, const bool* give_up) {
            return check_column(column, boxes, workers_[static_cast<std::size_t>(this_thread())].sweep, collect,
                                home, give_up);
        });
    next_order_.insert(next_order_.end(), oversized_list_.begin(), oversized_list_.end());
    SMB_ASSERT(next_order_.size() == boxes.size(), "every box has exactly one home cell");
    return moves;
}

/// Runs work(item, collect, home, give_up) for the items 0..count-1 (columns, oversized boxes)
/// so that their pairs reach `report`, and their home boxes `home`, in item order whatever the
/// number of threads. One thread: straight through. Several: rounds of items shared among the
/// threads, each item's pairs buffered; while the threads work on one round, the calling thread
/// first hands the previous round on (so the caller's sink only ever runs on the thread that
/// called detect(), and the hand-over overlaps the work). An item whose pairs outgrow its
/// buffer's cap (a crowd of identical boxes: billions of pairs) gives up and is run again alone
/// when its turn comes, straight into the caller's sink, so memory stays bounded.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Report, class Work>
std::size_t PersistentCutPipeline<Real, Dim, Input>::in_ordered_rounds(std::size_t count, Report& report,
                                                                std::vector<Position>& home, Work&& work) {
    auto report_ids = [&](Position a, Position b, bool sure = false) {
        if (confirmed(a, b, sure)) report(id_at(a), id_at(b));
    };
    std::size_t moves = 0;
    if (threads_ == 1) {
        for (std::size_t item = 0; item < count; ++item) moves += work(item, report_ids, home, nullptr);
        return moves;
    }
    const std::size_t round = 8 * static_cast<std::size_t>(threads_);
    run_in_ordered_rounds(
        threads_, count, round, blocks_,
        [&](std::size_t item, BlockOutput& block) {
            block.filled = 0;
            block.home.clear();
            block.overflowed = false;
            block.moves = 0;
            // The pairs are written by index into an array grown by doubling, not push_back:
            // one store a pair, where push_back was a call out of line (as in PairOutput).
            auto collect = [&block, this](Position x, Position y, bool sure = false) {
                if (block.filled == kBlockPairCap) {
                    block.overflowed = true;
                    return;
                }
                if (!confirmed(x, y, sure)) return;
                if (block.filled == block.pairs.size())
                    block.pairs.resize(std::min(kBlockPairCap, std::max<std::size_t>(1024, 2 * block.filled)));
                block.pairs[block.filled++] = ordered_pair(id_at(x), id_at(y));
            };
            block.moves = work(item, collect, block.home, &block.overflowed);
        },
        [&](std::size_t item, BlockOutput& block) {
            if (block.overflowed) {
                moves += work(item, report_ids, home, nullptr);
            } else {
                report.append(std::span<const Pair>(block.pairs.data(), block.filled));
                home.insert(home.end(), block.home.begin(), block.home.end());
                moves += block.moves;
            }
        });
    return moves;
}

/// Checks the k cells of one column in order; stops early once *give_up is set.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Collect>
std::size_t PersistentCutPipeline<Real, Dim, Input>::check_column(std::size_t column, std::span<const Box<Real, Dim>> boxes,
                                                           CellPairs<Real, Dim>& sweep, Collect& collect,
                                                           std::vector<Position>& home, const bool* give_up) {
    const std::vector<Position>& cells = lists_[cells_list_];
    const std::vector<std::uint32_t>& cell_begin = begin_[cells_list_];
    const std::uint32_t k = cuts_.segments();
    std::size_t moves = 0;
    for (std::size_t cell = column * k; cell < (column + 1) * k; ++cell) {
        if (give_up != nullptr && *give_up) break;
        const std::uint32_t first = cell_begin[cell];
        const std::uint32_t size = cell_begin[cell + 1] - first;
        if (size == 0) continue;
        // The boxes two cells ahead lie in a few runs of the ordered array, mostly in L3: ask
        // for them now so that they arrive while this cell is checked.
        constexpr std::size_t ahead = 2;
        if (cell + ahead + 1 < cell_begin.size()) {
            for (std::uint32_t i = cell_begin[cell + ahead]; i < cell_begin[cell + ahead + 1]; ++i) {
                __builtin_prefetch(&boxes[cells[i]]);
                __builtin_prefetch(own_ids_ ? static_cast<const void*>(&ordered_ids_[cells[i]])
                                            : static_cast<const void*>(&order_[cells[i]]));
            }
        }
        const std::span<const Position> entries(cells.data() + first, size);
        moves += own_ids_ ? sweep.check(entries, boxes, std::span<const BoxId>(ordered_ids_), floor_of_cell(cell),
                                        collect, home)
                          : sweep.check(entries, boxes, std::span<const Slot>(order_), floor_of_cell(cell), collect,
                                        home);
    }
    return moves;
}

/// Calls visit(cell, floor) for every cell whose segments `box` touches on every level.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Visit>
void PersistentCutPipeline<Real, Dim, Input>::for_each_cell_covering(const Box<Real, Dim>& box, Visit&& visit) const {
    const std::uint32_t k = cuts_.segments();
    CellFloor<Real, Dim> floor{};
    auto descend = [&](auto& self, int level, std::size_t group) -> void {
        if (level == Dim) {
            visit(group, floor);
            return;
        }
        const int axis = axis_of_level(level);
        const std::span<const Real> planes = cuts_.cuts(level, group);
        const std::uint32_t lo = segment_of(planes, box.min[axis]);
        const std::uint32_t hi = segment_of(planes, box.max[axis]);
        for (std::uint32_t s = lo; s <= hi; ++s) {
            floor[axis] = cuts_.lower(level, group, s);
            self(self, level + 1, group * k + s);
        }
    };
    descend(descend, 0, 0);
}

/// Oversized boxes are in no cell. Each is tested against the boxes of every cell it covers,
/// under the same lower-corner rule as the cells (so a pair is reported once even when the
/// other box is registered in several of those cells), and against the oversized boxes after
/// it in x order by a sweep on x.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Report>
void PersistentCutPipeline<Real, Dim, Input>::check_oversized(std::span<const Box<Real, Dim>> boxes, Report& report) {
    std::vector<Position> no_home;  // oversized boxes have no home cell
    in_ordered_rounds(oversized_list_.size(), report, no_home,
                      [&](std::size_t index, auto& collect, std::vector<Position>&, const bool* give_up) {
                          check_one_oversized(index, boxes, collect, give_up);
                          return std::size_t{0};
                      });
}

/// Oversized box number `index` (in x order) against the boxes of the cells it covers and
/// against the oversized boxes after it; stops early once *give_up is set.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Collect>
void PersistentCutPipeline<Real, Dim, Input>::check_one_oversized(std::size_t index, std::span<const Box<Real, Dim>> boxes,
                                                          Collect& collect, const bool* give_up) const {
    const std::vector<Position>& sorted = oversized_list_;  // in x order (detect())
    const Position big = sorted[index];
    const Box<Real, Dim>& a = boxes[big];
    for_each_cell_box_overlapping(a, boxes, [&](Position other) { collect(big, other); }, give_up);
    for (std::size_t j = index + 1; j < sorted.size() && boxes[sorted[j]].min[0] <= a.max[0]; ++j) {
        if (overlaps(a, boxes[sorted[j]])) collect(big, sorted[j]);
    }
}

/// Calls visit(position) for every box registered in the cells `query` covers whose box in
/// `boxes` overlaps `query`, once: a box registered in several of those cells is visited by the
/// cell holding the lower corner of the two boxes' intersection (the cells' own rule: every box
/// registered in a cell, and `query`, have min below the cell's upper plane on every axis).
/// Stops early once *give_up is set.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Visit>
void PersistentCutPipeline<Real, Dim, Input>::for_each_cell_box_overlapping(const Box<Real, Dim>& query,
                                                                            std::span<const Box<Real, Dim>> boxes,
                                                                            Visit&& visit, const bool* give_up) const {
    const std::vector<Position>& cells = lists_[cells_list_];
    const std::vector<std::uint32_t>& cell_begin = begin_[cells_list_];
    for_each_cell_covering(query, [&](std::size_t cell, const CellFloor<Real, Dim>& floor) {
        if (give_up != nullptr && *give_up) return;
        for (std::uint32_t i = cell_begin[cell]; i < cell_begin[cell + 1]; ++i) {
            const Box<Real, Dim>& box = boxes[cells[i]];
            if (!overlaps(query, box)) continue;
            bool owned = true;
            for (int axis = 0; axis < Dim; ++axis)
                owned = owned && (query.min[axis] >= floor[axis] || box.min[axis] >= floor[axis]);
            if (owned) visit(cells[i]);
        }
    });
}

/// After detect(), next_order_ holds the order the cells and ordered_ were built on: position
/// to slot.
template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Visit>
void PersistentCutPipeline<Real, Dim, Input>::for_each_held_overlapping(const Box<Real, Dim>& query,
                                                                        Visit&& visit) const {
    if (cuts_.segments() == 0 || ordered_.empty()) return;
    const std::vector<Slot>& slot_at = next_order_;
    for_each_cell_box_overlapping(query, std::span<const Box<Real, Dim>>(ordered_),
                                  [&](Position position) { visit(slot_at[position]); });
    for (const Position big : oversized_list_) {
        if (ordered_[big].min[0] > query.max[0]) break;  // in x order (run_levels())
        if (overlaps(query, ordered_[big])) visit(slot_at[big]);
    }
}

template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::check_invariants(std::span<const Box<Real, Dim>> boxes) const {
    // Every box that is not oversized is registered in exactly the cells it covers.
    const std::vector<Slot>& cells = lists_[cells_list_];
    const std::vector<std::uint32_t>& cell_begin = begin_[cells_list_];
    std::vector<std::uint32_t> registered(boxes.size(), 0);
    for (std::size_t cell = 0; cell + 1 < cell_begin.size(); ++cell) {
        for (std::uint32_t i = cell_begin[cell]; i < cell_begin[cell + 1]; ++i) {
            SMB_ASSERT(!oversized_[cells[i]], "an oversized box is in a cell");
            ++registered[cells[i]];
        }
    }
    for (std::size_t slot = 0; slot < boxes.size(); ++slot) {
        if (oversized_[slot]) continue;
        std::uint32_t covered = 0;
        for_each_cell_covering(boxes[slot], [&](std::size_t cell, const CellFloor<Real, Dim>&) {
            ++covered;
            const auto* first = cells.data() + cell_begin[cell];
            const auto* last = cells.data() + cell_begin[cell + 1];
            SMB_ASSERT(std::find(first, last, static_cast<Slot>(slot)) != last, "a box misses a cell it covers");
        });
        SMB_ASSERT(covered == registered[slot], "a box is in a cell it does not cover");
    }
}

}  // namespace smb::detail
