// SPDX-License-Identifier: MIT
#pragma once
// The default pipeline: SMB's levels of axial cuts, with the cuts kept from one step to the next
// (cut_tree.hpp) so that every level is a linear bucketing pass instead of a sort. Per detection:
//   1. the boxes are copied in last step's cell order (cell_order.hpp), or, where it follows no
//      cell, grouped by column (sampled_cuts.hpp, column_presort.hpp);
//   2. each level registers every box in the segments it touches (level_regrouping.hpp); a box
//      spanning more than two is oversized. By default x is left uncut: each cell is a whole
//      column of the level above, with no pass of its own;
//   3. each cell is checked (cell_checks.hpp, cell_pairs.hpp), which writes the next order; a
//      column is left in x order, so that a query reads only what it reaches along x (cells.hpp);
//   4. oversized boxes are tested against the cells they cover and against one another.
// docs/algorithm.md gives the proof that each overlapping pair is reported exactly once.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "core/held_box.hpp"
#include "core/id_index.hpp"
#include "core/input_retest.hpp"
#include "core/slot_renumbering.hpp"
#include "core/stopwatch.hpp"
#include "core/thread_team.hpp"
#include "cuts/cell_checks.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/column_presort.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/level_regrouping.hpp"
#include "cuts/sampled_cuts.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

/// The shape of the cells: whole columns of the levels above x, swept on x (the default: the
/// fewest registrations and candidates per box), or cut on every axis into cells of about the
/// target population, which answer a query box by the few small cells it covers.
enum class CellShape { columns, cut_on_every_axis };

template <std::floating_point Real, int Dim, std::floating_point Input = Real>
class PersistentCutPipeline {
public:
    explicit PersistentCutPipeline(CellShape shape = CellShape::columns) {
        regrouping_.set_columns(shape == CellShape::columns);
    }

    // The order between detections (CellOrder); the carried ids lie in the spare list.
    void fold_removals(const SlotRenumbering& renumbering) {
        cell_order_.fold_removals(renumbering, regrouping_.spare_list());
    }
    void follow_own_order() { cell_order_.follow_own_order(); }
    [[nodiscard]] std::size_t listed() const noexcept { return cell_order_.listed(); }
    void forget_slots_from(std::size_t n) { cell_order_.forget_slots_from(n); }
    [[nodiscard]] std::span<const Slot> order() const noexcept { return cell_order_.order(); }

    /// Reports every overlapping pair of `input` once (report.append(pairs in a < b order) for
    /// runs, report(id_a, id_b) for single pairs): box `slot` of `input` under id ids[slot], or
    /// under id `slot` where `ids` is empty. Floats held for double input are shifted by the
    /// origin (set_origin()) and rounded (held_box.hpp), each pair they cannot settle tested
    /// again on `input`. `ids_kept`: ids[slot] names the box the last detection saw at `slot`,
    /// but where fold_removals() moved it (a World's store).
    template <class Report>
    void detect(std::span<const Box<Input, Dim>> input, std::span<const BoxId> ids, const DetectionSettings& settings,
                Report& report, DetectProfile& profile, bool ids_kept = false);

    /// Whether the next detection copies the boxes grouped by column (column_presort.hpp).
    [[nodiscard]] bool presorting() const noexcept { return presort_.sorting(); }

    /// Where held coordinates start from (rounded input only); a new origin forgets every plane.
    void set_origin(const std::array<Input, Dim>& origin) {
        origin_ = origin;
        forget_cuts();
        order_state_ = OrderState::fresh;
    }

    /// The bounds of the boxes the next detection gets (rounded input only): held boxes that
    /// overlap by held_sure_margin() on every axis then need no second test on the input.
    void set_scene_bounds(const std::array<Input, Dim>& lo, const std::array<Input, Dim>& hi) {
        if constexpr (kRounded) sure_margin_ = held_sure_margin<Input, Dim>(origin_, lo, hi);
    }

    /// Calls visit(slot) once for every box of the last detection whose held box overlaps `query`
    /// (closed), through the cells that `query` covers and the oversized boxes; valid until the
    /// next detection or change (the skin list's neighbour search, cells.hpp).
    template <class Visit>
    void for_each_held_overlapping(const Box<Real, Dim>& query, Visit&& visit) const {
        SMB_ASSERT(!cell_order_.own_ids(), "the cells of a pipeline given ids are lent after it (spare_list())");
        const std::span<const Box<Real, Dim>> boxes = cell_order_.boxes();
        if (cuts_.cells() == 0 || boxes.empty()) return;
        const std::span<const Slot> slot_at = cell_order_.copied_from();
        regrouping_.cells(cuts_).for_each_box_overlapping(query, boxes,
                                                          [&](Position position) { visit(slot_at[position]); });
        for (const Position big : regrouping_.oversized()) {
            if (boxes[big].min[0] > query.max[0]) break;  // in x order
            if (overlaps(query, boxes[big])) visit(slot_at[big]);
        }
    }

    /// Pairs that the held floats could not settle, tested again on the input, in the last
    /// detection (rounded input only).
    [[nodiscard]] std::size_t retested() const noexcept { return retested_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return cell_order_.bytes_held() + cuts_.bytes_held() + regrouping_.bytes_held() + checks_.bytes_held() +
               presort_.bytes_held();
    }

private:
    /// Floats held for double input: every pair the floats pass is confirmed on the input.
    static constexpr bool kRounded = !std::same_as<Real, Input>;
    static_assert(!kRounded || std::same_as<Real, float>, "rounded input is held as floats");

    void plan_segments(std::size_t n, const DetectionSettings& settings);

    /// The planes, their planned shape and the judgement of the copy by column, all forgotten.
    void forget_cuts() {
        cuts_.forget();
        planned_segments_ = 0;
        presort_.forget();
    }

    /// Held boxes at positions a and b overlap: true when their input boxes do too. `sure`:
    /// the cell check found them overlapping by the sure margin (set_scene_bounds()).
    /// Inlined: called for every pair the cells report, and for exact input it does nothing.
    [[nodiscard, gnu::always_inline]] inline bool confirmed(Position a, Position b, bool sure) {
        if constexpr (kRounded) sure = sure || surely_overlap(cell_order_.boxes()[a], cell_order_.boxes()[b]);
        // The input is indexed by slot, which the order still gives while a detection runs.
        return confirmed_on_input<Real>(input_, cell_order_.order(), a, b, sure, [this] {
            // Counted per thread would be exact too; a relaxed atomic is simpler and rare.
            std::atomic_ref<std::size_t>(retested_).fetch_add(1, std::memory_order_relaxed);
        });
    }

    std::span<const Box<Input, Dim>> input_;  // the boxes of the detection under way
    std::array<Input, Dim> origin_{};
    float sure_margin_ = std::numeric_limits<float>::infinity();  // infinity: proves nothing
    std::size_t retested_ = 0;
    int threads_ = 1;
    CellOrder<Real, Dim, Input> cell_order_;
    CutTree<Real, Dim> cuts_;
    std::uint32_t planned_segments_ = 0;  // segments per group before a layer reshapes the cuts
    LevelRegrouping<Real, Dim> regrouping_;
    CellChecks<Real, Dim> checks_;
    ColumnPresort<Real, Dim, Input> presort_;
    /// What the order follows: no cell (cold: the first detection, a new origin) or last step's.
    enum class OrderState { fresh, follows_cells };
    OrderState order_state_ = OrderState::fresh;
};

/// About (N / target population)^(1/Dim) segments per group, so that cells hold about the target
/// number of boxes; changed only when N has moved by more than a quarter, since a new count
/// forgets every plane. A layer a few boxes thick then moves segments from its level to the
/// other (sampled_cuts.hpp).
template <std::floating_point Real, int Dim, std::floating_point Input>
void PersistentCutPipeline<Real, Dim, Input>::plan_segments(std::size_t n, const DetectionSettings& settings) {
    const double cells = static_cast<double>(n) / static_cast<double>(settings.target_cell_population);
    const double ideal = std::clamp(std::pow(cells, 1.0 / Dim), 1.0, double{CutTree<Real, Dim>::kMaxSegments});
    const double current = planned_segments_;
    if (current == 0 || ideal > 1.25 * current || ideal < 0.8 * current) {
        planned_segments_ = static_cast<std::uint32_t>(std::lround(ideal));
        cuts_.reshape(planned_segments_);
    }
}

template <std::floating_point Real, int Dim, std::floating_point Input>
template <class Report>
void PersistentCutPipeline<Real, Dim, Input>::detect(std::span<const Box<Input, Dim>> input, std::span<const BoxId> ids,
                                                     const DetectionSettings& settings, Report& report,
                                                     DetectProfile& profile, bool ids_kept) {
    const std::size_t n = input.size();
    input_ = input;
    retested_ = 0;
    cell_order_.list_arrivals(n);
    if (n == 0) {
        forget_cuts();
        return;
    }
    const std::uint32_t segments_before = planned_segments_;
    plan_segments(n, settings);
    threads_ = thread_count(settings);
    // A cold order (first detection, new cut counts, new origin) follows no cell and the cuts
    // have no planes: the levels above the columns are cut from a sample first, and the boxes
    // copied grouped by column (sampled_cuts.hpp).
    const bool cold = order_state_ == OrderState::fresh || planned_segments_ != segments_before;

    Stopwatch phase{settings.profile};
    const bool presorted = !cold && presort_.sorting();
    auto copy_by_column = [&] {
        cell_order_.copy_by_column(
            input, ids, origin_, cuts_.groups(Dim - 1),
            [this](const Box<Real, Dim>& box) { return cuts_.column_of(box); }, threads_);
    };
    if (cold) {
        presort_.forget();
        // A temporary: its buffers are needed only now, and a pipeline holds nothing for it.
        SampledCuts<Real, Dim, Input>().cut(input, origin_, cuts_);
        profile.quantile_seconds += phase.lap();
        copy_by_column();
        // The entries now come column by column: the hint is worth trying on every level.
        regrouping_.set_without_hint(false);
    } else if (presorted) {
        presort_.note_columns(input, origin_, cuts_);
        copy_by_column();
    } else {
        cell_order_.copy(input, ids, origin_, threads_, regrouping_.spare_list());
    }
    profile.copy_seconds += phase.seconds();
    const std::span<const Box<Real, Dim>> boxes = cell_order_.boxes();
    auto id_at = [this](Position position) { return cell_order_.id_at(position); };
    // The levels' per-entry segments live where the check then writes the next order: the two
    // are never needed at once, and sharing saves 4 bytes a box.
    const double cutting =
        regrouping_.run(boxes, cuts_, threads_, id_at, settings.profile, profile, cell_order_.next());
    if (!cold && !presorted) presort_.judge(regrouping_.first_level_misses());
    profile.quantile_seconds += cutting;
    profile.cut_regroup_seconds += phase.lap() - cutting;
    profile.cells += cuts_.cells();

    auto confirm = [this](Position a, Position b, bool sure) { return confirmed(a, b, sure); };
    const SweptColumns<Real> columns = regrouping_.swept_columns();
    const CheckedCells<Real, Dim, CellOrder<Real, Dim, Input>, decltype(confirm)> checked{
        regrouping_.cells(cuts_), columns, regrouping_.oversized(), boxes, cell_order_, confirm};
    profile.sort_moves += checks_.check(checked, sure_margin_, threads_, report, cell_order_.next());
    profile.oversized_boxes += regrouping_.oversized().size();
    profile.check_seconds += phase.seconds();
#ifdef SMB_VALIDATE
    regrouping_.cells(cuts_).check_registrations(boxes, regrouping_.oversized_flags());
#endif
    // How far boxes moved in the order is no sign of motion (the boxes a step adds shift every
    // later place): the hint's judgement counts misses instead. A next detection that copies by
    // column reads the ids from the input: none are carried for it.
    cell_order_.advance(threads_, ids_kept && !presort_.sorting(), regrouping_.spare_list());
    order_state_ = OrderState::follows_cells;
}

}  // namespace smb::detail
