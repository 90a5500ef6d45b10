// SPDX-License-Identifier: MIT
#pragma once
// The paper's own pipeline (its Sections 2.4 and 3), chosen by WorldSettings::pipeline =
// Pipeline::paper_lists. It keeps the paper's data structures (corner lists sorted by DIS on
// every level, flag matrix, mask array) and is what docs/reproduction.md measures against the
// paper; the default pipeline (persistent_cut_pipeline.hpp) is the faster one. Generalised from
// the 2D example to Dim levels: level l sorts the projections on axis Dim-1-l (y then x in 2D, z then
// y then x in 3D), grouped by the segments of level l-1. docs/algorithm.md maps every step of
// the paper to the functions below.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "core/assert.hpp"
#include "core/slot_renumbering.hpp"
#include "core/stopwatch.hpp"
#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"
#include "paper/cell_check.hpp"
#include "paper/cell_lists.hpp"
#include "paper/global_local_map.hpp"
#include "paper/mask_array.hpp"
#include "paper/oversized_sweep.hpp"
#include "paper/paper_level.hpp"
#include "paper/shell_sort.hpp"
#include "paper/singular_regroup.hpp"
#include "smb/held_precision.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class PaperPipeline {
public:
    explicit PaperPipeline(const WorldSettings& settings)
        : segment_rule_(settings.segment_rule), target_cell_population_(settings.target_cell_population) {}

    /// Renumbers every list after BoxStore::compact() dropped removed slots, keeping each
    /// list's order (the paper's remark 3 of Section 2.4: renumber, never rebuild).
    void fold_removals(const SlotRenumbering& renumbering) {
        std::size_t still_listed = 0;
        for (std::size_t s = 0; s < listed_; ++s) still_listed += renumbering(static_cast<Slot>(s)) != kNoSlot ? 1 : 0;
        for (int depth = 0; depth < Dim; ++depth) levels_[depth].renumber(renumbering, depth + 1);
        listed_ = still_listed;
    }

    /// Slots [0, listed()) are in the lists; later ones arrived since the last detection.
    [[nodiscard]] std::size_t listed() const noexcept { return listed_; }
    /// The lists hold the boxes as they are; none before a detection of some boxes.
    [[nodiscard]] HeldPrecision precision() const noexcept {
        if (listed_ == 0) return HeldPrecision::none;
        return std::is_same_v<Real, float> ? HeldPrecision::floats : HeldPrecision::doubles;
    }
    [[nodiscard]] static std::size_t retested() noexcept { return 0; }

    /// Reports every overlapping pair of `boxes` (valid; slot s of a BoxStore at index s) as
    /// report(slot_a, slot_b); times its phases where `timed`.
    template <class Report>
    void detect(std::span<const Box<Real, Dim>> boxes, Report& report, bool timed, DetectProfile& profile) {
        boxes_ = boxes;
        const std::size_t n = boxes_.size();
        if (n > 0) {
            choose_cuts();
            const std::array<Real, Dim> shortest = shortest_segments<Real, Dim>(segment_rule_, boxes_);
            fit_capacity(segment_of_, n << Dim);  // the deepest level's length: the longest
            Stopwatch phase{timed};
            double sorting = 0;
            for (int depth = 0; depth < Dim; ++depth) {
                Level& level = levels_[depth];
                refresh_keys(level, depth);
                collect_arrivals(depth);
                const std::size_t length = n << (depth + 1);
                fit_capacity(level.list, length);
                if (depth == 0) {
                    // Step 1 of Section 3: the first list is one section; arrivals are merged in
                    // sorted, then DIS restores the order that the motion disturbed.
                    if (!arrivals_.empty()) {
                        std::sort(arrivals_.begin(), arrivals_.end(), EntryLess{});
                        merge_from_back(level.list, arrivals_);
                    }
                    level.section_begin.assign({0U, static_cast<std::uint32_t>(level.list.size())});
                } else {
                    // Steps 4-7 of Section 3: regroup by the parent level's cut, whose index array
                    // segment_of_ still holds.
                    const Level& parent = levels_[depth - 1];
                    section_scratch_.resize(parent.segment_begin.size());
                    for (std::size_t j = 0; j < section_scratch_.size(); ++j) {
                        section_scratch_[j] = 2 * parent.segment_begin[j];
                    }
                    regroup_by_parent_segment<Real>(level.list, level.section_begin, arrivals_, segment_of_,
                                                    section_scratch_, regroup_);
                    profile.level_singular_items[static_cast<std::size_t>(depth)] =
                        regroup_.singular.size() - arrivals_.size();
                    level.section_begin.swap(section_scratch_);
                }
                SMB_ASSERT(level.list.size() == (n << (depth + 1)), "a list lost or gained items");
                const Stopwatch sort_watch{timed};
                const DisWork work = level.sort();
                sorting += sort_watch.seconds();
                level.dis.learn(work);
                profile.sort_moves += work.moves();
                profile.level_sort_moves[static_cast<std::size_t>(depth)] = work.moves();
                profile.level_sort_comparisons[static_cast<std::size_t>(depth)] = work.comparisons;
                profile.level_sort_fallback_items[static_cast<std::size_t>(depth)] = work.fallback_items;
                level.cut(cuts_, segment_of_, shortest[static_cast<std::size_t>(depth)]);
                if (depth == 0) oversized_.assign(n, 0);
                mark_oversized(depth);
            }
            listed_ = n;
            release_oversized_scratch();
            oversized_count_ = static_cast<std::size_t>(std::count(oversized_.begin(), oversized_.end(), 1));
            build_cell_lists();
            profile.list_sort_seconds = sorting;
            profile.cut_regroup_seconds = phase.lap() - sorting;
            profile.cells = levels_[Dim - 1].segment_begin.size() - 1;
            profile.oversized_boxes = oversized_count_;

            profile.largest_cell_boxes = check_cells(report);
            if (oversized_count_ > 0) {
                oversized_sweep_.run(levels_[0].list, oversized_, boxes_, report);
            }
            profile.check_seconds = phase.seconds();
#ifdef SMB_VALIDATE
            check_invariants();
#endif
        } else {
            for (auto& level : levels_) {
                level.list.clear();
                level.section_begin.clear();
            }
            listed_ = 0;
        }
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = 0;
        for (const Level& level : levels_) bytes += level.bytes_held();
        for (const auto& cell_list : cell_lists_) bytes += cell_list.capacity() * sizeof(Item);
        bytes += cell_cursor_.capacity() * sizeof(std::uint32_t);
        bytes += arrivals_.capacity() * sizeof(Entry) + segment_of_.capacity() * sizeof(SegmentId);
        bytes += section_scratch_.capacity() * sizeof(std::uint32_t);
        bytes += oversized_.capacity() + regroup_.bytes_held() + mask_.bytes_held() + map_.bytes_held();
        bytes += checker_.bytes_held() + oversized_sweep_.bytes_held();
        return bytes;
    }

    using Entry = AxisEntry<Real>;
    using Level = PaperLevel<Real>;  // the paper's Y1, X12 in 2D; Z1, Y12, X123 in 3D

    // Read-only views of the lists as the last detection left them, so that a test can hold
    // them against the paper's worked example.
    [[nodiscard]] const Level& level(int depth) const noexcept { return levels_[static_cast<std::size_t>(depth)]; }
    [[nodiscard]] std::span<const Item> cell_list(int depth) const noexcept {
        return cell_lists_[static_cast<std::size_t>(depth)];
    }
    [[nodiscard]] const std::vector<std::uint8_t>& oversized() const noexcept { return oversized_; }
    /// The index array of the deepest cut: the cell of every corner.
    [[nodiscard]] std::span<const SegmentId> cell_of() const noexcept { return segment_of_; }
    [[nodiscard]] SegmentId cuts() const noexcept { return cuts_; }

private:
    static constexpr int axis_of_level(int level) noexcept { return Dim - 1 - level; }
    /// The coordinate of `item` of level `depth`: its end of its box on the level's axis.
    [[nodiscard]] Real key_of(Item item, int depth) const noexcept {
        const auto& box = boxes_[item >> (depth + 1)];
        return end_of(item) == 0 ? box.min[axis_of_level(depth)] : box.max[axis_of_level(depth)];
    }

    /// Number of segments per section: about (N / target population)^(1/Dim) on every level, so
    /// that cells hold about the target number of boxes. It changes only when N has moved by more
    /// than a quarter from the value it was chosen for, because a new count renumbers every section
    /// and turns every item singular for one step.
    void choose_cuts() {
        const double cells = static_cast<double>(boxes_.size()) / static_cast<double>(target_cell_population_);
        const double ideal = std::max(1.0, std::pow(cells, 1.0 / Dim));
        const double current = static_cast<double>(cuts_);
        if (cuts_ == 0 || ideal > 1.25 * current || ideal < 0.8 * current) {
            cuts_ = static_cast<SegmentId>(std::lround(ideal));
        }
    }
    // The span, axis and shift held in locals: the loop's stores to the keys would otherwise have
    // it read the members again for every entry.
    void refresh_keys(Level& level, int depth) {
        const auto boxes = boxes_;
        const int axis = axis_of_level(depth);
        const int shift = depth + 1;
        for (Entry& entry : level.list) {
            const auto& box = boxes[entry.item >> shift];
            entry.key = end_of(entry.item) == 0 ? box.min[axis] : box.max[axis];
        }
    }
    /// The items of the boxes inserted since the last detection, for level `depth`.
    void collect_arrivals(int depth) {
        arrivals_.clear();
        const int shift = depth + 1;
        for (std::size_t slot = listed_; slot < boxes_.size(); ++slot) {
            const Item first = static_cast<Item>(slot) << shift;
            for (Item item = first; item < first + (Item{1} << shift); ++item)
                arrivals_.push_back(Entry{key_of(item, depth), item});
        }
    }
    /// A box is oversized when, on some level and for some of its faces, its min and max fall more
    /// than one segment apart: the segment between would not hold it (the paper's Fig. 5). Each
    /// level is judged right after its cut, while the index array holds its segments.
    void mark_oversized(int depth) {
        const std::size_t n = boxes_.size();
        for (std::size_t slot = 0; slot < n; ++slot) {
            if (oversized_[slot]) continue;
            const Item first = static_cast<Item>(slot) << (depth + 1);
            for (Item parent = 0; parent < (Item{1} << depth); ++parent) {
                const Item min_item = first | (parent << 1);
                if (segment_of_[min_item | 1U] - segment_of_[min_item] > 1) {
                    oversized_[slot] = 1;
                    break;
                }
            }
        }
    }
    /// The first detection (and any step that inserts or moves many boxes) fills the arrival and
    /// stack buffers with up to 2^Dim items per box. Keeping that capacity would double the memory
    /// of a world whose later steps change little, so a buffer much larger than this step needed is
    /// given back; steady steps that need about the same amount each time keep theirs.
    void release_oversized_scratch() {
        auto trim = [](auto& buffer) {
            if (buffer.capacity() > 64 * 1024 && buffer.capacity() > 4 * buffer.size()) {
                std::remove_reference_t<decltype(buffer)> smaller;
                smaller.reserve(2 * buffer.size());
                smaller.assign(buffer.begin(), buffer.end());
                buffer.swap(smaller);
            }
        };
        trim(arrivals_);
        trim(regroup_.singular);
    }
    /// Steps 9-11 of Section 3 (cell_lists.hpp): the paper's Y2 in 2D; Y2 and Z2 in 3D.
    void build_cell_lists() {
        const Level& deepest = levels_[Dim - 1];
        for (int depth = 0; depth + 1 < Dim; ++depth) {
            fit_capacity(cell_lists_[static_cast<std::size_t>(depth)], deepest.list.size());
            regroup_by_cell(ItemsOf<Real>(levels_[depth].list), Dim - 1 - depth, segment_of_, deepest.segment_begin,
                            cell_lists_[static_cast<std::size_t>(depth)], cell_cursor_);
        }
    }
    /// Steps 12-16 of Section 3: every cell in (slab, column, cell) order, with the mask array
    /// updated after each cell and after each finished segment of an upper level. Returns the most
    /// boxes a cell held.
    template <class Report>
    std::size_t check_cells(Report& report) {
        const std::size_t n = boxes_.size();
        const Level& deepest = levels_[Dim - 1];
        const auto& cell_begin = deepest.segment_begin;
        const std::size_t cells = cell_begin.size() - 1;
        mask_.reset(n);
        map_.reset(n);
        std::array<std::size_t, Dim> cells_per_segment{};  // of each upper level
        for (int depth = 0; depth < Dim; ++depth) {
            std::size_t count = 1;
            for (int below = depth + 1; below < Dim; ++below) count *= cuts_;
            cells_per_segment[static_cast<std::size_t>(depth)] = count;
        }
        typename CellChecker<Real, Dim>::CellLists lists;
        std::size_t largest = 0;
        for (std::size_t cell = 0; cell < cells; ++cell) {
            const std::uint32_t first = cell_begin[cell];
            const std::size_t size = cell_begin[cell + 1] - first;
            if (size != 0) {
                for (int depth = 0; depth + 1 < Dim; ++depth) {
                    lists.upper[static_cast<std::size_t>(depth)] =
                        std::span<const Item>(cell_lists_[static_cast<std::size_t>(depth)].data() + first, size);
                }
                lists.deepest = std::span<const Entry>(deepest.list.data() + first, size);
                checker_.check(lists, oversized_, boxes_, map_, mask_, report);
                largest = std::max(largest, map_.boxes().size());
                for (const std::uint32_t slot : map_.boxes()) mask_.mark_cell_done(slot, Dim - 1);
                map_.clear_cell();
            }
            // An empty cell may still close a column or a slab: the mask must learn it all the same.
            for (int depth = Dim - 2; depth >= 0; --depth) {
                const std::size_t per_segment = cells_per_segment[static_cast<std::size_t>(depth)];
                if ((cell + 1) % per_segment != 0) break;
                for (std::uint32_t i = cell_begin[cell + 1 - per_segment]; i < cell_begin[cell + 1]; ++i) {
                    const Item slot = deepest.list[i].item >> Dim;
                    if (!oversized_[slot]) mask_.mark_segment_done(slot, depth);
                }
            }
        }
        return largest;
    }
    void check_invariants() const {
        const std::size_t n = boxes_.size();
        std::vector<SegmentId> parent_segment_of;
        std::vector<SegmentId> segment_of;
        for (int depth = 0; depth < Dim; ++depth) {
            const Level& level = levels_[depth];
            const int shift = depth + 1;
            segment_of.assign(level.list.size(), 0);
            for (std::size_t s = 0; s + 1 < level.segment_begin.size(); ++s) {
                for (std::uint32_t i = level.segment_begin[s]; i < level.segment_begin[s + 1]; ++i) {
                    segment_of[level.list[i].item] = static_cast<SegmentId>(s);
                }
            }
            SMB_ASSERT(level.list.size() == (n << shift), "list length");
            std::vector<std::uint8_t> seen(level.list.size(), 0);
            for (std::size_t j = 0; j + 1 < level.section_begin.size(); ++j) {
                for (std::uint32_t i = level.section_begin[j]; i < level.section_begin[j + 1]; ++i) {
                    const Entry& entry = level.list[i];
                    SMB_ASSERT(entry.item < seen.size() && !seen[entry.item], "list is a permutation");
                    seen[entry.item] = 1;
                    SMB_ASSERT(entry.key == key_of(entry.item, depth), "key matches its box");
                    if (i > level.section_begin[j]) {
                        SMB_ASSERT(!entry_less(entry, level.list[i - 1]), "section is sorted");
                    }
                    if (depth > 0) {
                        SMB_ASSERT(parent_segment_of[entry.item >> 1] == j, "item is in its parent's section");
                    }
                }
            }
            parent_segment_of.swap(segment_of);
        }
        SMB_ASSERT(parent_segment_of == segment_of_, "index array agrees with the deepest cut");
    }

    SegmentRule segment_rule_;
    std::size_t target_cell_population_;
    std::span<const Box<Real, Dim>> boxes_;  // of the detection under way

    std::array<Level, Dim> levels_;
    std::array<std::vector<Item>, Dim - 1> cell_lists_;  // the paper's Y2 (2D); Y2, Z2 (3D)
    std::vector<std::uint32_t> cell_cursor_;
    std::vector<Entry> arrivals_;
    std::vector<SegmentId> segment_of_;           // index array of the level cut last
    std::vector<std::uint32_t> section_scratch_;  // the regrouped sections' offsets
    std::vector<std::uint8_t> oversized_;
    std::size_t oversized_count_ = 0;
    RegroupScratch<Real> regroup_;
    MaskArray mask_;
    GlobalLocalMap map_;
    CellChecker<Real, Dim> checker_;
    OversizedSweep<Real, Dim> oversized_sweep_;

    std::size_t listed_ = 0;  // slots [0, listed_) are in the lists; later ones arrived since
    SegmentId cuts_ = 0;      // segments per section on every level
};

}  // namespace smb::detail
