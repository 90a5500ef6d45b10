// SPDX-License-Identifier: MIT
#pragma once
// The check of the persistent-cut pipeline's cells (cell_pairs.hpp, one column of cells after
// another) and of its oversized boxes, shared among the threads, with the pairs reaching the
// caller in the same order whatever their number.

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "core/bulk_vector.hpp"
#include "core/growth.hpp"
#include "core/ordered_rounds.hpp"
#include "core/pair_output.hpp"
#include "core/prefetch.hpp"
#include "core/thread_team.hpp"
#include "core/tuning.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/cell_pairs.hpp"
#include "cuts/cells.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// What the checks of one detection read: the cells and the oversized boxes (in x order) of the
/// regrouping, the ordered boxes, the ids of their positions (order: a CellOrder), and
/// confirm(a, b, sure), which says whether a pair the held boxes pass holds for the input too
/// (`sure`: the cell check proved it by the sure margin).
template <std::floating_point Real, int Dim, class Order, class Confirm>
struct CheckedCells {
    Cells<Real, Dim> cells;
    SweptColumns<Real> columns;  // not empty: every cell is a column, swept and written back
    std::span<const Position> oversized;
    std::span<const Box<Real, Dim>> boxes;
    const Order& order;
    Confirm& confirm;
};

template <std::floating_point Real, int Dim>
class CellChecks {
public:
    /// Pairs one column may hold while the threads check a round (4 MiB); see in_ordered_rounds().
    static constexpr std::size_t kBlockPairCap = tuning::block_pair_cap;

    /// Reports every pair of the cells, then of the oversized boxes (report(a, b), or
    /// report.append(pairs) for runs), on `threads` threads. Writes every box once to `home`: each
    /// cell's home boxes (whose lower corner it holds), cell by cell, then the oversized boxes.
    /// Returns the insertion-sort moves of the swept cells.
    template <class Checked, class Report>
    std::size_t check(const Checked& checked, float sure_margin, int threads, Report& report,
                      BulkVector<Position>& home) {
        threads_ = threads;
        cell_pairs_.resize(threads);
        gather_visitors(checked);
        const std::size_t moves = check_cells(checked, sure_margin, report, home);
        check_oversized(checked, report);
        return moves;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes =
            cell_pairs_.bytes_held([](const CellPairs<Real, Dim>& pairs) { return pairs.bytes_held(); });
        bytes += blocks_.capacity() * sizeof(BlockOutput) + swept_oversized_.capacity() * sizeof(Position);
        if (visitors_) bytes += sizeof(Visitors) + visitors_->bytes_held();
        for (const BlockOutput& block : blocks_)
            bytes += block.pairs.capacity() * sizeof(Pair) + block.home.capacity() * sizeof(Position);
        return bytes;
    }

private:
    /// The pairs and home boxes of one block of cells (a column), handed on in block order so
    /// that the report is the same whatever the number of threads.
    struct alignas(64) BlockOutput {
        std::vector<Pair> pairs;  // its first `filled` hold this block's pairs
        std::size_t filled = 0;
        BulkVector<Position> home;
        std::size_t moves = 0;
        bool overflowed = false;
    };

    template <class Checked, class Report>
    std::size_t check_cells(const Checked& checked, float sure_margin, Report& report, BulkVector<Position>& home);
    template <class Checked, class Report, class Work>
    std::size_t in_ordered_rounds(const Checked& checked, std::size_t count, Report& report, BulkVector<Position>& home,
                                  Work&& work);
    template <class Checked, class Collect>
    std::size_t check_column(const Checked& checked, std::size_t column, CellPairs<Real, Dim>& cell_pairs,
                             Collect& collect, BulkVector<Position>& home, const bool* give_up);
    template <class Checked>
    void gather_visitors(const Checked& checked);
    template <class Checked, class Report>
    void check_oversized(const Checked& checked, Report& report);

    PerThread<CellPairs<Real, Dim>> cell_pairs_;
    std::vector<BlockOutput> blocks_;  // one per block of a round of cell checks
    // What the oversized boxes' sweep lists as at home (all of them; check_cells() writes their
    // home): kept, so that a detection allocates nothing there.
    BulkVector<Position> swept_oversized_;
    /// The oversized boxes that cover each cell, in x order: cell c's are
    /// boxes[begin[c], begin[c + 1]); `begin` empty where no box is oversized.
    struct Visitors {
        BulkVector<Position> begin;
        BulkVector<Position> boxes;
        [[nodiscard]] std::size_t bytes_held() const noexcept {
            return (begin.capacity() + boxes.capacity()) * sizeof(Position);
        }
    };
    // Held apart, made when a box is first oversized: most scenes have none, and a World or
    // Detector holds a pipeline of each precision.
    std::unique_ptr<Visitors> visitors_;
    int threads_ = 1;
};

/// The cells are checked column by column (a column: the k cells of one group of the deepest
/// level), in column order, so the report does not depend on the thread count.
template <std::floating_point Real, int Dim>
template <class Checked, class Report>
std::size_t CellChecks<Real, Dim>::check_cells(const Checked& checked, float sure_margin, Report& report,
                                               BulkVector<Position>& home) {
    const std::span<const Box<Real, Dim>> boxes = checked.boxes;
    home.clear();
    reserve_with_slack(home, boxes.size());
    for (CellPairs<Real, Dim>& cell_pairs : cell_pairs_) cell_pairs.set_sure_margin(sure_margin);
    const std::size_t moves = in_ordered_rounds(
        checked, checked.cells.cuts->groups(Dim - 1), report, home,
        [&](std::size_t column, auto& collect, BulkVector<Position>& column_home, const bool* give_up) {
            return check_column(checked, column, cell_pairs_.mine(), collect, column_home, give_up);
        });
    home.insert(home.end(), checked.oversized.begin(), checked.oversized.end());
    SMB_ASSERT(home.size() == boxes.size(), "every box has exactly one home cell");
    return moves;
}

/// Runs work(item, collect, home, give_up) for the items 0..count-1 (columns, oversized boxes)
/// so that their pairs reach `report`, and their home boxes `home`, in item order whatever the
/// number of threads: straight through on one, else in ordered rounds (ordered_rounds.hpp), so
/// that the caller's sink runs only on the thread that called detect(). An item whose pairs
/// outgrow kBlockPairCap (a crowd of identical boxes) gives up and is run again alone, straight
/// into the sink, when its turn comes.
template <std::floating_point Real, int Dim>
template <class Checked, class Report, class Work>
std::size_t CellChecks<Real, Dim>::in_ordered_rounds(const Checked& checked, std::size_t count, Report& report,
                                                     BulkVector<Position>& home, Work&& work) {
    // The ids of the positions, read once here: the order does not change while the cells are
    // checked, and a pair is a few instructions, where reading them through `checked` after each
    // report costs a chain of dependent loads.
    const bool wide = checked.order.wide();
    const BoxId* const wide_ids = checked.order.wide_ids().data();
    const std::uint32_t* const ids = checked.order.narrow_ids().data();
    auto id_at = [wide, wide_ids, ids](Position position) { return wide ? wide_ids[position] : BoxId{ids[position]}; };
    auto report_ids = [&report, &checked, id_at](Position a, Position b, bool sure = false) {
        if (checked.confirm(a, b, sure)) report(id_at(a), id_at(b));
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
            // one store a pair, where push_back is a call out of line (as in PairOutput).
            auto collect = [&block, &checked, id_at](Position x, Position y, bool sure = false) {
                if (block.filled == kBlockPairCap) {
                    block.overflowed = true;
                    return;
                }
                if (!checked.confirm(x, y, sure)) return;
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
template <std::floating_point Real, int Dim>
template <class Checked, class Collect>
std::size_t CellChecks<Real, Dim>::check_column(const Checked& checked, std::size_t column,
                                                CellPairs<Real, Dim>& cell_pairs, Collect& collect,
                                                BulkVector<Position>& home, const bool* give_up) {
    const std::span<const Box<Real, Dim>> boxes = checked.boxes;
    const std::span<const Position> cells = checked.cells.entries;
    const std::span<const std::uint32_t> cell_begin = checked.cells.begin;
    const std::uint32_t k = checked.cells.cuts->segments(Dim - 1);
    const bool wide = checked.order.wide();
    const std::span<const BoxId> wide_ids = checked.order.wide_ids();
    const std::span<const std::uint32_t> ids = checked.order.narrow_ids();
    // The boxes of the cells ahead lie in a few runs of the ordered array, mostly beyond L2: ask
    // for them (and for their ids, which the report reads) while this cell is checked.
    auto prefetch_entries = [&](std::size_t from_cell, std::size_t to_cell) {
        if (to_cell >= cell_begin.size()) return;
        for (std::uint32_t i = cell_begin[from_cell]; i < cell_begin[to_cell]; ++i) {
            prefetch_whole(&boxes[cells[i]]);
            __builtin_prefetch(wide ? static_cast<const void*>(&wide_ids[cells[i]])
                                    : static_cast<const void*>(&ids[cells[i]]));
        }
    };
    // A column holds all its boxes in its first cell, the others being empty, so that the cells
    // two ahead are empty too: the whole next column is asked for instead (about a thousand
    // boxes and ids, which L2 holds while this column is checked).
    const bool swept_columns = !checked.columns.entries.empty();
    if (swept_columns) prefetch_entries((column + 1) * k, (column + 2) * k);
    std::size_t moves = 0;
    for (std::size_t cell = column * k; cell < (column + 1) * k; ++cell) {
        if (give_up != nullptr && *give_up) break;
        const std::uint32_t first = cell_begin[cell];
        const std::uint32_t size = cell_begin[cell + 1] - first;
        if (size == 0) continue;
        constexpr std::size_t ahead = 2;  // cells of about the target population
        if (!swept_columns) prefetch_entries(cell + ahead, cell + ahead + 1);
        const std::span<const Position> entries(cells.data() + first, size);
        if (swept_columns) {
            // Swept at every size, so that every column is left in x order for its queries.
            moves += checked.order.with_ids([&](auto names) {
                return cell_pairs.check_by_sweep(entries, boxes, names, checked.cells.floor_of(cell), collect, home);
            });
            const std::span<const std::uint32_t> sorted = cell_pairs.swept_positions();
            std::copy(sorted.begin(), sorted.end(), checked.columns.entries.begin() + first);
            checked.columns.widest[cell] = cell_pairs.widest_x();
        } else {
            moves += checked.order.with_ids([&](auto names) {
                return cell_pairs.check(entries, boxes, names, checked.cells.floor_of(cell), collect, home);
            });
        }
        if (!visitors_ || visitors_->begin.empty()) continue;
        const std::span<const Position> visitors(visitors_->boxes.data() + visitors_->begin[cell],
                                                 visitors_->begin[cell + 1] - visitors_->begin[cell]);
        if (!visitors.empty()) cell_pairs.check_visitors(visitors, boxes, checked.cells.floor_of(cell), collect);
    }
    return moves;
}

/// Lists, cell by cell, the oversized boxes that cover it (in x order), which the check of each
/// cell then tests against the cell's boxes as it has them laid out (CellPairs::check_visitors()).
template <std::floating_point Real, int Dim>
template <class Checked>
void CellChecks<Real, Dim>::gather_visitors(const Checked& checked) {
    if (checked.oversized.empty()) {
        if (visitors_) visitors_->begin.clear();
        return;
    }
    if (!visitors_) visitors_ = std::make_unique<Visitors>();
    BulkVector<Position>& begin = visitors_->begin;
    const std::size_t cells = checked.cells.begin.size() - 1;
    begin.assign(cells + 2, 0);
    const std::span<const Box<Real, Dim>> boxes = checked.boxes;
    for (const Position big : checked.oversized)
        checked.cells.for_each_covering(boxes[big],
                                        [&](std::size_t cell, const CellFloor<Real, Dim>&) { ++begin[cell + 2]; });
    for (std::size_t c = 2; c < begin.size(); ++c) begin[c] += begin[c - 1];
    visitors_->boxes.resize(begin.back());
    for (const Position big : checked.oversized)
        checked.cells.for_each_covering(boxes[big], [&](std::size_t cell, const CellFloor<Real, Dim>&) {
            visitors_->boxes[begin[cell + 1]++] = big;
        });
    begin.pop_back();
}

/// Oversized boxes are in no cell. Each is tested against the boxes of every cell it covers by
/// that cell's check (gather_visitors()), under the same lower-corner rule as the cells (so a
/// pair is reported once even when the other box is registered in several of those cells); here,
/// against one another, swept on x as one cell that has no lower planes, so that every pair is
/// its own: eight candidates a compare and no branch per candidate, where a test per pair
/// mispredicts on most (with 1% of the boxes two to eight times the others' size, those tests
/// took as long as every cell's sweep). Their home is written by check_cells(), not here.
template <std::floating_point Real, int Dim>
template <class Checked, class Report>
void CellChecks<Real, Dim>::check_oversized(const Checked& checked, Report& report) {
    if (checked.oversized.size() < 2) return;
    constexpr Real kNoPlane = -std::numeric_limits<Real>::infinity();
    CellFloor<Real, Dim> everywhere{};
    everywhere.fill(kNoPlane);
    swept_oversized_.clear();
    in_ordered_rounds(checked, 1, report, swept_oversized_,
                      [&](std::size_t, auto& collect, BulkVector<Position>& unused_home, const bool*) {
                          CellPairs<Real, Dim>& cell_pairs = cell_pairs_.mine();
                          return checked.order.with_ids([&](auto ids) {
                              return cell_pairs.check_by_sweep(checked.oversized, checked.boxes, ids, everywhere,
                                                               collect, unused_home);
                          });
                      });
}

}  // namespace smb::detail
