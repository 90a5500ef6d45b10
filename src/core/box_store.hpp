// SPDX-License-Identifier: MIT
#pragma once
// The boxes of a world under their caller-chosen ids, in dense slots. Slots are what the SMB
// lists number (the paper's "AABB n"); ids are what the caller sees. Changes made between two
// detections are recorded here and folded into the lists by the next detection.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/bulk_vector.hpp"
#include "core/growth.hpp"
#include "core/id_index.hpp"
#include "core/invalid_box.hpp"
#include "core/slot_renumbering.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class BoxStore {
public:
    [[nodiscard]] std::size_t size() const noexcept { return slot_of_id_.size(); }
    [[nodiscard]] std::size_t slot_count() const noexcept { return boxes_.size(); }
    [[nodiscard]] bool has_removals() const noexcept { return removed_ != 0; }
    [[nodiscard]] bool contains(BoxId id) const { return slot_of_id_.contains(id); }

    [[nodiscard]] const Box<Real, Dim>& box_at(Slot slot) const noexcept { return boxes_[slot]; }
    [[nodiscard]] BoxId id_at(Slot slot) const noexcept { return ids_[slot]; }
    [[nodiscard]] bool alive(Slot slot) const noexcept { return alive_[slot] != 0; }
    [[nodiscard]] std::span<const Box<Real, Dim>> boxes() const noexcept { return boxes_; }
    [[nodiscard]] std::span<const BoxId> ids() const noexcept { return ids_; }
    /// Counts the calls that may have changed the boxes held (insert, remove, update, assign,
    /// clear): what was built from the boxes is current while this count is unchanged. A
    /// detection renumbers slots (compact) but keeps every id's box, so it counts nothing.
    [[nodiscard]] std::uint64_t changes() const noexcept { return changes_; }

    [[nodiscard]] Slot slot_of(BoxId id) const {
        const Slot slot = slot_of_id_.find(id);
        if (slot == kNoSlot) throw UnknownIdError("box " + std::to_string(id) + " is not in the world");
        return slot;
    }

    void insert(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes) {
        ++changes_;
        require_same_length(ids.size(), boxes.size(), "insert");
        validate_boxes(ids, boxes);
        reserve_for(ids.size(), ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()));
        // The index itself finds repeats, within the batch as well as against the world; the
        // ids this batch added are taken out again before the error leaves.
        const auto first = static_cast<Slot>(boxes_.size());
        for (std::size_t i = 0; i < ids.size(); ++i) {
            if (!slot_of_id_.insert(ids[i], first + static_cast<Slot>(i))) {
                for (std::size_t j = 0; j < i; ++j) slot_of_id_.erase(ids[j]);
                throw DuplicateIdError("box " + std::to_string(ids[i]) + " is already in the world");
            }
        }
        boxes_.insert(boxes_.end(), boxes.begin(), boxes.end());
        ids_.insert(ids_.end(), ids.begin(), ids.end());
        alive_.resize(alive_.size() + ids.size(), 1);
    }

    void remove(std::span<const BoxId> ids) {
        ++changes_;
        std::vector<Slot> slots;
        slots.reserve(ids.size());
        for (const BoxId id : ids) slots.push_back(slot_of(id));
        // A repeated id names a slot twice: marked on the first visit, found on the second,
        // and every mark is undone before the error leaves.
        constexpr std::uint8_t kNamed = 2;
        for (std::size_t i = 0; i < slots.size(); ++i) {
            if (alive_[slots[i]] == kNamed) {
                for (std::size_t j = 0; j < i; ++j) alive_[slots[j]] = 1;
                throw DuplicateIdError("box " + std::to_string(ids[i]) + " is named twice in one remove");
            }
            alive_[slots[i]] = kNamed;
        }
        reserve_removed_log(ids.size());
        for (std::size_t i = 0; i < ids.size(); ++i) kill(ids[i], slots[i]);
    }

    void update(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes) {
        ++changes_;
        require_same_length(ids.size(), boxes.size(), "update");
        // Every id is looked up twice rather than once into a list of slots: a simulation
        // updates every box every step, and the list would be an allocation per step. The first
        // pass checks the boxes and the ids together (at 1M boxes each pass is a trip to memory);
        // only where it fails are they checked again apart, for the error a caller expects first.
        for (std::size_t i = 0; i < ids.size(); ++i) {
            if (!is_valid(boxes[i]) || !slot_of_id_.contains(ids[i])) [[unlikely]] {
                validate_boxes(ids, boxes);
                for (const BoxId id : ids) (void)slot_of(id);
            }
        }
        for (std::size_t i = 0; i < ids.size(); ++i) boxes_[slot_of_id_.find(ids[i])] = boxes[i];
    }

    void assign(std::span<const Box<Real, Dim>> boxes) {
        ++changes_;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (!is_valid(boxes[i])) throw InvalidBoxError(describe_invalid_box(static_cast<BoxId>(i), boxes[i]));
        }
        const auto n = static_cast<BoxId>(boxes.size());
        // Ids at or above n go first, so that the slots they free are compacted together.
        std::vector<std::pair<BoxId, Slot>> doomed;
        slot_of_id_.for_each([&](BoxId id, Slot slot) {
            if (id >= n) doomed.emplace_back(id, slot);
        });
        std::size_t fresh = 0;
        for (BoxId i = 0; i < n; ++i) fresh += contains(i) ? 0 : 1;
        reserve_for(fresh, n == 0 ? 0 : n - 1);
        reserve_removed_log(doomed.size());
        for (const auto& [id, slot] : doomed) kill(id, slot);
        for (BoxId i = 0; i < n; ++i) {
            const Slot slot = slot_of_id_.find(i);
            if (slot != kNoSlot) {
                boxes_[slot] = boxes[i];
            } else {
                append(i, boxes[i]);
            }
        }
    }

    void clear() {
        ++changes_;
        boxes_.clear();
        ids_.clear();
        alive_.clear();
        slot_of_id_.clear();
        removed_ = 0;
        removed_log_.clear();
    }

    /// Hands over the ids removed since the last call (for pair events: an id removed and
    /// inserted again is a new box) and starts a new log, keeping the capacity.
    void take_removed_log(std::vector<BoxId>& ids) {
        ids.swap(removed_log_);
        removed_log_.clear();
    }

    /// Drops the removed slots and returns how every old slot was renumbered, for the SMB lists
    /// (the paper's Section 2.4, remark 3). The first `listed` slots are those the pipeline lists,
    /// the others arrived since. A removed listed slot takes the last living listed box, so only
    /// as many listed boxes move as were removed (keeping every box in its order moved every box
    /// after the first removal: 570 MB a step at 10M boxes); the arrivals close up behind, in
    /// their order. Allocates before it changes anything.
    SlotRenumbering compact(std::size_t listed) {
        const std::size_t n = boxes_.size();
        listed = std::min(listed, n);
        std::vector<Slot> holes;
        holes.reserve(std::min(removed_, listed));
        for (std::size_t s = 0; s < listed; ++s) {
            if (alive_[s] == 0) holes.push_back(static_cast<Slot>(s));
        }
        const std::size_t kept = listed - holes.size();
        SlotRenumbering renumbering(kept, n);
        // Every hole below `kept` has a donor: the slots from `kept` to `listed` hold as many
        // living boxes as there are holes below `kept`.
        std::size_t donor = kept;
        for (const Slot hole : holes) {
            if (hole >= kept) break;
            renumbering.mark_removed_below(hole);
            while (alive_[donor] == 0) ++donor;
            move_box(static_cast<Slot>(donor), hole);
            renumbering.mark_moved(static_cast<Slot>(donor), hole);
            ++donor;
        }
        std::size_t next = kept;
        for (std::size_t s = listed; s < n; ++s) {
            if (alive_[s] == 0) continue;
            if (s != next) move_box(static_cast<Slot>(s), static_cast<Slot>(next));
            renumbering.mark_moved(static_cast<Slot>(s), static_cast<Slot>(next));
            ++next;
        }
        boxes_.resize(next);
        ids_.resize(next);
        alive_.resize(next);
        removed_ = 0;
        return renumbering;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return boxes_.capacity() * sizeof(Box<Real, Dim>) + ids_.capacity() * sizeof(BoxId) + alive_.capacity() +
               slot_of_id_.bytes_held() + removed_log_.capacity() * sizeof(BoxId);
    }

private:
    static void require_same_length(std::size_t ids, std::size_t boxes, const char* what) {
        if (ids != boxes) {
            throw ArgumentError(std::string(what) + ": " + std::to_string(ids) + " ids but " + std::to_string(boxes) +
                                " boxes");
        }
    }
    static void validate_boxes(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes) {
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (!is_valid(boxes[i])) throw InvalidBoxError(describe_invalid_box(ids[i], boxes[i]));
        }
    }
    /// Room for `extra` more boxes, whose largest id is `largest`.
    void reserve_for(std::size_t extra, BoxId largest) {
        // The deepest SMB list numbers 2^Dim corners per slot in 32 bits.
        constexpr std::size_t max_slots = (std::size_t{1} << (32 - Dim)) - 1;
        if (boxes_.size() + extra > max_slots)
            throw ArgumentError("a " + std::to_string(Dim) + "D world holds at most " + std::to_string(max_slots) +
                                " boxes (including boxes removed since the last detection)");
        reserve_with_slack(boxes_, boxes_.size() + extra);
        reserve_with_slack(ids_, ids_.size() + extra);
        reserve_with_slack(alive_, alive_.size() + extra);
        slot_of_id_.reserve(extra, largest);
    }
    void append(BoxId id, const Box<Real, Dim>& box) {
        const auto slot = static_cast<Slot>(boxes_.size());
        boxes_.push_back(box);
        ids_.push_back(id);
        alive_.push_back(1);
        slot_of_id_.insert(id, slot);
    }
    void move_box(Slot from, Slot to) {
        boxes_[to] = boxes_[from];
        ids_[to] = ids_[from];
        alive_[to] = 1;
        slot_of_id_.move(ids_[to], to);
    }
    /// Before any change, so that logging cannot fail half-way through a removal.
    void reserve_removed_log(std::size_t extra) {
        const std::size_t size = removed_log_.size() + extra;
        if (size > removed_log_.capacity()) removed_log_.reserve(std::max(size, 2 * removed_log_.capacity()));
    }
    void kill(BoxId id, Slot slot) {
        removed_log_.push_back(id);
        alive_[slot] = 0;
        slot_of_id_.erase(id);
        ++removed_;
    }

    BulkVector<Box<Real, Dim>> boxes_;
    BulkVector<BoxId> ids_;
    BulkVector<std::uint8_t> alive_;
    IdIndex slot_of_id_;
    std::size_t removed_ = 0;
    std::vector<BoxId> removed_log_;
    std::uint64_t changes_ = 0;
};

}  // namespace smb::detail
