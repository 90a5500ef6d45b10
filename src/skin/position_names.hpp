// SPDX-License-Identifier: MIT
#pragma once
// The names the skin list (skin_list.hpp) reports its positions under: the caller's keys, read
// per position so that a candidate's report reads nothing at random, or none, when a box is
// named by its index.
//
// Reading every position's key again each detection is a second random gather beside the
// boxes' own (at 1M boxes, 7 of a World's 42 ms). A World's store keeps each slot's id but where
// a removal moved another box into the slot (BoxStore::compact()), so with kept keys only those
// slots, the new ones and the fresh positions are read again.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/bulk_vector.hpp"
#include "core/id_index.hpp"
#include "core/prefetch.hpp"
#include "core/slot_renumbering.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

class PositionNames {
public:
    using Position = std::uint32_t;

    /// This detection's keys (per slot; empty: each box is named by its slot). `kept`: keys[i]
    /// names the box the last detection saw at slot i, but at the slots noted by fold_removals().
    void follow(std::span<const BoxId> keys, bool kept) {
        keys_ = keys;
        kept_ = kept;
    }
    [[nodiscard]] bool named() const noexcept { return !keys_.empty(); }
    /// Whether every position's key must be read again in this detection's scan.
    [[nodiscard]] bool reread() const noexcept { return !keys_.empty() && !kept_; }

    /// Every position's key, in the order of `slot_of` (a rebuild).
    void gather(std::span<const Slot> slot_of) {
        rekeyed_.clear();
        if (keys_.empty()) return;
        key_of_.resize(slot_of.size());
        for (std::size_t p = 0; p < slot_of.size(); ++p) key_of_[p] = keys_[slot_of[p]];
    }
    void prefetch(Slot slot) const { prefetch_whole(&keys_[slot]); }
    void read(Position p, Slot slot) {
        if (!keys_.empty()) key_of_[p] = keys_[slot];
    }
    void append(Slot slot) {
        if (!keys_.empty()) key_of_.push_back(keys_[slot]);
    }

    /// A World's store moved boxes into the slots of removed ones.
    void fold_removals(const SlotRenumbering& renumbering) {
        if (key_of_.empty()) return;
        renumbering.for_each_change([this](Slot, Slot now) {
            if (now != kNoSlot) rekeyed_.push_back(now);
        });
    }
    /// The keys of the slots fold_removals() noted, below `known` slots of `position_of`.
    void read_moved(std::span<const Position> position_of, std::size_t count) {
        if (kept_) {
            for (const Slot slot : rekeyed_) {
                if (slot < std::min(count, position_of.size())) key_of_[position_of[slot]] = keys_[slot];
            }
        }
        rekeyed_.clear();
    }

    /// The names of the positions: keys, or else `slot_of` itself.
    [[nodiscard]] std::span<const BoxId> keys_of_positions() const noexcept { return key_of_; }
    [[nodiscard]] BoxId operator()(Position p, std::span<const Slot> slot_of) const noexcept {
        return keys_.empty() ? BoxId{slot_of[p]} : key_of_[p];
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return key_of_.capacity() * sizeof(BoxId) + rekeyed_.capacity() * sizeof(Slot);
    }

private:
    std::span<const BoxId> keys_;  // per slot: the name it is reported under (empty: the slot)
    bool kept_ = false;
    BulkVector<BoxId> key_of_;   // per position, with keys: keys_[slot_of[p]]
    std::vector<Slot> rekeyed_;  // slots a World's store filled since the last detection
};

}  // namespace smb::detail
