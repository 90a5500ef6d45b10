// SPDX-License-Identifier: MIT
#pragma once
// The boxes a region received, kept from step to step so that a step needs only what changed:
// boxes inserted or moved (an upsert) and boxes that left the region or the scene (a removal).

#include <cstddef>
#include <unordered_map>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::mpi::detail {

template <class Box>
class RegionStore {
public:
    /// The region's boxes, their ids and the rank holding each, in one dense array for the
    /// Detector (a removal moves the last box into the hole).
    [[nodiscard]] const std::vector<BoxId>& ids() const noexcept { return ids_; }
    [[nodiscard]] const std::vector<Box>& boxes() const noexcept { return boxes_; }
    [[nodiscard]] const std::vector<int>& holders() const noexcept { return holders_; }
    [[nodiscard]] std::size_t size() const noexcept { return ids_.size(); }

    void clear() {
        ids_.clear();
        boxes_.clear();
        holders_.clear();
        slots_.clear();
    }

    /// Room for `count` boxes without rehashing the ids' slots.
    void reserve(std::size_t count) { slots_.reserve(count); }

    /// Forgets box `id`; a box not here is ignored.
    void remove(BoxId id) {
        const auto found = slots_.find(id);
        if (found == slots_.end()) return;
        const std::size_t slot = found->second;
        slots_.erase(found);
        const std::size_t last = ids_.size() - 1;
        if (slot != last) {
            ids_[slot] = ids_[last];
            boxes_[slot] = boxes_[last];
            holders_[slot] = holders_[last];
            slots_[ids_[slot]] = slot;
        }
        ids_.pop_back();
        boxes_.pop_back();
        holders_.pop_back();
    }

    /// Box `id` as `box`, held by rank `holder`: new here, or in place of its last copy.
    void upsert(BoxId id, const Box& box, int holder) {
        const auto [found, inserted] = slots_.try_emplace(id, ids_.size());
        if (!inserted) {
            boxes_[found->second] = box;
            holders_[found->second] = holder;
            return;
        }
        ids_.push_back(id);
        boxes_.push_back(box);
        holders_.push_back(holder);
    }

private:
    std::vector<BoxId> ids_;
    std::vector<Box> boxes_;
    std::vector<int> holders_;
    std::unordered_map<BoxId, std::size_t> slots_;
};

}  // namespace smb::mpi::detail
