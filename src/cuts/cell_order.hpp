// SPDX-License-Identifier: MIT
#pragma once
// The order the persistent-cut pipeline reads the boxes in: every slot once, cell by cell as the
// last detection left them (x-sorted within a swept cell), and the boxes and ids copied in that
// order once per detection. Every later pass reads the copy almost sequentially, where reading
// the caller's array by slot would miss the cache on nearly every box. The entries of the levels
// and cells are positions in the copy, not slots.

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "core/bulk_vector.hpp"
#include "core/growth.hpp"
#include "core/held_box.hpp"
#include "core/id_index.hpp"
#include "core/prefetch.hpp"
#include "core/slot_renumbering.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// A place in the ordered copy of the boxes (CellOrder).
using Position = std::uint32_t;

template <std::floating_point Real, int Dim, std::floating_point Input>
class CellOrder {
public:
    /// Drops removed slots from the order and renumbers the others (BoxStore::compact(), which
    /// leaves the listed boxes in the first slots); the carried ids follow (advance()).
    void fold_removals(const SlotRenumbering& renumbering, BulkVector<std::uint32_t>& carried_ids) {
        std::size_t write = 0;
        std::size_t carried = 0;
        for (std::size_t read = 0; read < order_.size(); ++read) {
            const Slot now = renumbering(order_[read]);
            if (now == kNoSlot) continue;
            // A renumbered slot holds the same box, under the same id.
            if (read < carried_count_) carried_ids[carried++] = carried_ids[read];
            order_[write++] = now;
        }
        order_.resize(write);
        listed_ = write;
        carried_count_ = carried;
    }

    /// The caller moved the box of order()[p] to slot p, for every p: the order becomes the
    /// slots themselves.
    void follow_own_order() {
        for (std::size_t p = 0; p < order_.size(); ++p) order_[p] = static_cast<Slot>(p);
        forget_carried();
    }

    /// Slots [0, listed()) are in the order; later ones arrived since the last detection.
    [[nodiscard]] std::size_t listed() const noexcept { return listed_; }

    /// Forgets the slots from `n` on: a Detector's caller passed fewer boxes than last time.
    void forget_slots_from(std::size_t n) {
        if (n >= listed_) return;
        forget_carried();
        std::erase_if(order_, [n](Slot slot) { return slot >= n; });
        listed_ = std::min(listed_, n);
    }

    /// Appends the slots that arrived since the last detection, for a detection of `n` boxes.
    void list_arrivals(std::size_t n) {
        reserve_with_slack(order_, n);
        for (std::size_t slot = listed_; slot < n; ++slot) order_.push_back(static_cast<Slot>(slot));
        listed_ = n;
        SMB_ASSERT(order_.size() == n, "the order holds every box once");
    }

    /// Every slot once: last detection's cells. While a detection runs, the slot each position
    /// of the copy holds.
    [[nodiscard]] std::span<const Slot> order() const noexcept { return order_; }

    /// After a detection: the slot each position of its copy holds (the order it was made in).
    [[nodiscard]] std::span<const Slot> copied_from() const noexcept { return next_order_; }

    /// Copies the boxes (held from `origin` where Real rounds Input) and their ids in order, the
    /// ids advance() carried read from `carried_ids`.
    void copy(std::span<const Box<Input, Dim>> store_boxes, std::span<const BoxId> store_ids,
              const std::array<Input, Dim>& origin, int threads, const BulkVector<std::uint32_t>& carried_ids) {
        const std::size_t n = order_.size();
        size_copy(n, store_ids);
        // The ids carried from the last copy (advance()) are read in order; the others, from the
        // store like the boxes.
        const std::uint32_t* carried = carried_ids.data();
        const std::size_t carried_count = own_ids_ ? carried_count_ : 0;
        // Each box is a miss of its own (the store is in slot order, not cell order) and the loop
        // does little else, so the requests must start far ahead to keep enough in flight.
        constexpr std::size_t ahead = 64;
        const auto count = static_cast<std::ptrdiff_t>(n);
        BoxId high = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(| : high)
        for (std::ptrdiff_t j = 0; j < count; ++j) {
            const auto i = static_cast<std::size_t>(j);
            if (i + ahead < n) {
                prefetch_whole(&store_boxes[order_[i + ahead]]);
                if (own_ids_ && i + ahead >= carried_count) __builtin_prefetch(&store_ids[order_[i + ahead]]);
            }
            ordered_[i] = held_as<Real>(store_boxes[order_[i]], origin);
            if (own_ids_) {
                const BoxId id = i < carried_count ? BoxId{carried[i]} : store_ids[order_[i]];
                narrow_ids_[i] = static_cast<std::uint32_t>(id);
                high |= id >> 32;
            }
        }
        widen_ids_where_needed(high, store_ids);
#ifdef SMB_VALIDATE
        for (std::size_t i = 0; i < carried_count; ++i)
            SMB_ASSERT(id_at(static_cast<Position>(i)) == store_ids[order_[i]],
                       "a carried id names the box of its slot");
#endif
        forget_carried();
    }

    /// copy() where the order follows no cell (the first detection, new cuts, boxes that jumped
    /// across cells: column_presort.hpp): the order becomes the slots grouped by column_of(held
    /// box) (< `columns`), in slot order within a column, and each box is copied to its column's
    /// run by a counting sort: the caller's boxes are read twice in order, where sorting the
    /// order first and copying in it would read every box from a different place.
    template <class ColumnOf>
    void copy_by_column(std::span<const Box<Input, Dim>> store_boxes, std::span<const BoxId> store_ids,
                        const std::array<Input, Dim>& origin, std::size_t columns, ColumnOf&& column_of, int threads) {
        const std::size_t n = order_.size();
        SMB_ASSERT(store_boxes.size() == n, "the order holds every box once");
        forget_carried();
        size_copy(n, store_ids);
        // Each slot's column is held where the cell check writes the next order: no memory of
        // its own, and the check finds those pages mapped.
        resize_for_overwrite(next_order_, n);
        std::uint32_t* column_at = next_order_.data();
        const auto shares = static_cast<std::size_t>(threads);
        std::vector<std::uint32_t> cursor(shares * columns, 0U);
        auto share_begin = [&](std::size_t t) { return n * t / shares; };
#pragma omp parallel for num_threads(threads) schedule(static, 1)
        for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
            std::uint32_t* count = cursor.data() + static_cast<std::size_t>(t) * columns;
            for (std::size_t slot = share_begin(static_cast<std::size_t>(t));
                 slot < share_begin(static_cast<std::size_t>(t) + 1); ++slot) {
                const std::uint32_t column = column_of(held_as<Real>(store_boxes[slot], origin));
                column_at[slot] = column;
                ++count[column];
            }
        }
        // Offsets column by column, share by share, so that each column keeps the slot order.
        std::uint32_t offset = 0;
        for (std::size_t c = 0; c < columns; ++c) {
            for (std::size_t t = 0; t < shares; ++t) {
                const std::uint32_t here = cursor[t * columns + c];
                cursor[t * columns + c] = offset;
                offset += here;
            }
        }
        BoxId high = 0;
#pragma omp parallel for num_threads(threads) schedule(static, 1) reduction(| : high)
        for (std::ptrdiff_t t = 0; t < static_cast<std::ptrdiff_t>(shares); ++t) {
            std::uint32_t* next = cursor.data() + static_cast<std::size_t>(t) * columns;
            for (std::size_t slot = share_begin(static_cast<std::size_t>(t));
                 slot < share_begin(static_cast<std::size_t>(t) + 1); ++slot) {
                const std::uint32_t position = next[column_at[slot]]++;
                order_[position] = static_cast<Slot>(slot);
                ordered_[position] = held_as<Real>(store_boxes[slot], origin);
                if (own_ids_) {
                    narrow_ids_[position] = static_cast<std::uint32_t>(store_ids[slot]);
                    high |= store_ids[slot] >> 32;
                }
            }
        }
        widen_ids_where_needed(high, store_ids);
    }

    /// The boxes in order, as copied by the last copy().
    [[nodiscard]] std::span<const Box<Real, Dim>> boxes() const noexcept { return ordered_; }
    /// Whether the ids were given; else box `slot` has id `slot` (order()).
    [[nodiscard]] bool own_ids() const noexcept { return own_ids_; }
    /// Whether some id of the last copy needs more than 32 bits: the ids are then wide_ids().
    [[nodiscard]] bool wide() const noexcept { return wide_; }
    /// Unless wide(), the id of the box at each position: the given id, or its slot where none
    /// were given (while a detection runs, order_ still maps positions to slots, so slot ids need
    /// no array of their own). Ids are almost always counted from zero: 32 bits hold them, half
    /// the bytes to copy, keep and read at each pair of a 64-bit id.
    [[nodiscard]] std::span<const std::uint32_t> narrow_ids() const noexcept {
        return own_ids_ ? std::span<const std::uint32_t>(narrow_ids_) : std::span<const std::uint32_t>(order_);
    }
    [[nodiscard]] std::span<const BoxId> wide_ids() const noexcept { return wide_ids_; }
    /// use(ids) with the ids that name the positions, wide_ids() or narrow_ids(), for the
    /// passes that read them in a loop of their own.
    template <class Use>
    decltype(auto) with_ids(Use&& use) const {
        return wide_ ? use(wide_ids()) : use(narrow_ids());
    }

    [[nodiscard]] BoxId id_at(Position position) const noexcept {
        return wide_ ? wide_ids_[position] : BoxId{narrow_ids()[position]};
    }

    /// Where the cell check writes the positions of the home boxes, cell by cell: the next order.
    /// Until then, room the detection lends to the levels (LevelRegrouping::run()): what
    /// copied_from() held is not needed once a detection has begun.
    [[nodiscard]] BulkVector<Position>& next() noexcept { return next_order_; }

    /// Makes next() the order: the check wrote positions in the copy, the order holds their slots.
    /// Where each slot keeps its given id to the next detection but where fold_removals() moves
    /// it (`ids_kept`, a World's store), the ids, when all fit 32 bits, are carried into
    /// `carried_ids` (room the caller leaves alone until the next copy) in the next order, so
    /// that the next copy reads them in order instead of gathering them by slot.
    void advance(int threads, bool ids_kept, BulkVector<std::uint32_t>& carried_ids) {
        const std::size_t n = next_order_.size();
        const auto count = static_cast<std::ptrdiff_t>(n);
        if (!own_ids_ || !ids_kept || wide_) {
#pragma omp parallel for num_threads(threads) schedule(static)
            for (std::ptrdiff_t i = 0; i < count; ++i) next_order_[i] = order_[next_order_[i]];
            order_.swap(next_order_);
            return;
        }
        resize_for_overwrite(carried_ids, n);
        std::uint32_t* carried = carried_ids.data();
#pragma omp parallel for num_threads(threads) schedule(static)
        for (std::ptrdiff_t i = 0; i < count; ++i) {
            const Position position = next_order_[i];
            carried[i] = narrow_ids_[position];
            next_order_[i] = order_[position];
        }
        order_.swap(next_order_);
        carried_count_ = n;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (order_.capacity() + next_order_.capacity()) * sizeof(Slot) +
               ordered_.capacity() * sizeof(Box<Real, Dim>) + narrow_ids_.capacity() * sizeof(std::uint32_t) +
               wide_ids_.capacity() * sizeof(BoxId);
    }

private:
    void forget_carried() noexcept { carried_count_ = 0; }

    /// Room for n copied boxes, and for their ids where the caller gives them.
    void size_copy(std::size_t n, std::span<const BoxId> store_ids) {
        resize_for_overwrite(ordered_, n);
        own_ids_ = !store_ids.empty();
        if (own_ids_)
            resize_for_overwrite(narrow_ids_, n);
        else
            BulkVector<std::uint32_t>().swap(narrow_ids_);
    }

    /// After a copy that kept the low 32 bits of each id: where some id had more (`high`), the
    /// whole ids are gathered again (rare: ids made of hashes or handles); else none are held.
    void widen_ids_where_needed(BoxId high, std::span<const BoxId> store_ids) {
        wide_ = high != 0;
        if (!wide_) {
            BulkVector<BoxId>().swap(wide_ids_);
            return;
        }
        resize_for_overwrite(wide_ids_, order_.size());
        for (std::size_t p = 0; p < order_.size(); ++p) wide_ids_[p] = store_ids[order_[p]];
    }

    BulkVector<Slot> order_;                // every slot once: last step's cells, x-sorted within swept ones
    BulkVector<Position> next_order_;       // positions of the home boxes, cell by cell
    BulkVector<Box<Real, Dim>> ordered_;    // the boxes in order_'s order, copied each step
    BulkVector<std::uint32_t> narrow_ids_;  // and their ids, unless the ids are the slots or wide_
    BulkVector<BoxId> wide_ids_;            // their ids, where some id needs more than 32 bits
    bool own_ids_ = true;                   // ids were given; else box `slot` has id `slot`
    bool wide_ = false;                     // the last copy's ids are wide_ids_
    std::size_t listed_ = 0;                // slots [0, listed_) are in order_; later ones are new
    std::size_t carried_count_ = 0;         // order_'s first places whose ids advance() carried
};

}  // namespace smb::detail
