// SPDX-License-Identifier: MIT
#pragma once
// How BoxStore::compact() renumbered the slots: every old slot's new slot, or kNoSlot for a
// removed box. The compaction moves few boxes, so the map is a bit per slot below the moved
// range and a table for the range, not an array of every slot: a pipeline reads it in its lists'
// order, random in slots, and at 10M boxes a 40 MB array read so missed the cache and the TLB on
// nearly every entry.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/id_index.hpp"

namespace smb::detail {

class SlotRenumbering {
public:
    SlotRenumbering() = default;

    /// Slots below `kept` keep their number unless marked removed; slots from `kept` to
    /// `old_count` are removed unless mark_moved() gives them a new one.
    SlotRenumbering(std::size_t kept, std::size_t old_count)
        : kept_(kept), removed_below_((kept + 63) / 64, 0), moved_(old_count - kept, kNoSlot) {}

    void mark_removed_below(Slot slot) { removed_below_[slot / 64] |= std::uint64_t{1} << (slot % 64); }
    void mark_moved(Slot from, Slot to) { moved_[from - kept_] = to; }

    /// The new slot of `slot` (a slot of the store before the compaction), or kNoSlot.
    [[nodiscard]] Slot operator()(Slot slot) const noexcept {
        if (slot < kept_) return (removed_below_[slot / 64] >> (slot % 64)) & 1U ? kNoSlot : slot;
        const std::size_t above = slot - kept_;
        return above < moved_.size() ? moved_[above] : kNoSlot;
    }

    /// Calls change(old, now) for every slot removed (now == kNoSlot) or moved: first the removed
    /// slots below the moved range, then the moved range by ascending old slot, an order in which
    /// an array indexed by slot can follow in place (a box only moves down, to a slot visited).
    template <class Change>
    void for_each_change(Change&& change) const {
        for (std::size_t w = 0; w < removed_below_.size(); ++w) {
            for (std::uint64_t bits = removed_below_[w]; bits != 0; bits &= bits - 1)
                change(static_cast<Slot>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits))), kNoSlot);
        }
        for (std::size_t i = 0; i < moved_.size(); ++i) {
            const auto old = static_cast<Slot>(kept_ + i);
            if (moved_[i] != old) change(old, moved_[i]);
        }
    }

    /// Slots before the compaction.
    [[nodiscard]] std::size_t old_count() const noexcept { return kept_ + moved_.size(); }

private:
    std::size_t kept_ = 0;
    std::vector<std::uint64_t> removed_below_;  // a bit per slot below kept_: the box was removed
    std::vector<Slot> moved_;                   // new slots of the old slots from kept_ on
};

}  // namespace smb::detail
