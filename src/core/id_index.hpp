// SPDX-License-Identifier: MIT
#pragma once
// The map from the caller's ids to the store's slots. Simulations mostly number their bodies
// 0, 1, 2, ... (World::assign() does so by definition): those ids index a plain array of slots,
// 4 bytes per id and one access per lookup, where a node-based hash map costs about 48 bytes a
// box and a pointer chase. Ids far above the number of boxes go to a hash map instead, so the
// array never grows beyond about twice the number of boxes.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/bulk_vector.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

using Slot = std::uint32_t;
inline constexpr Slot kNoSlot = ~Slot{0};

class IdIndex {
public:
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

    /// The slot of `id`, or kNoSlot when it is absent.
    [[nodiscard]] Slot find(BoxId id) const {
        if (id < dense_.size() && dense_[id] != kNoSlot) return dense_[id];
        if (sparse_.empty()) return kNoSlot;
        const auto it = sparse_.find(id);
        return it == sparse_.end() ? kNoSlot : it->second;
    }
    [[nodiscard]] bool contains(BoxId id) const { return find(id) != kNoSlot; }

    /// Adds `id` at `slot`; false (and nothing changed) when `id` is present already.
    bool insert(BoxId id, Slot slot) {
        if (contains(id)) return false;
        if (id >= dense_.size() && id < dense_limit(count_ + 1)) grow_dense(id);
        if (id < dense_.size()) {
            dense_[id] = slot;
        } else {
            sparse_.emplace(id, slot);
        }
        ++count_;
        return true;
    }

    /// Moves a present id to another slot.
    void move(BoxId id, Slot slot) {
        if (id < dense_.size() && dense_[id] != kNoSlot) {
            dense_[id] = slot;
        } else {
            sparse_.at(id) = slot;
        }
    }

    /// Removes a present id.
    void erase(BoxId id) {
        if (id < dense_.size() && dense_[id] != kNoSlot) {
            dense_[id] = kNoSlot;
        } else {
            sparse_.erase(id);
        }
        --count_;
    }

    /// Makes room for `extra` more ids, the largest `largest`: the array grows at once to hold
    /// it where it will (one by one, a batch would double the array about log2(n) times, each a
    /// copy), and the hash map's buckets are reserved.
    void reserve(std::size_t extra, BoxId largest) {
        if (largest >= dense_.size() && largest < dense_limit(count_ + extra)) resize_dense(largest + 1);
        if (!sparse_.empty()) sparse_.reserve(sparse_.size() + extra);
    }

    void clear() {
        BulkVector<Slot>().swap(dense_);
        std::unordered_map<BoxId, Slot>().swap(sparse_);
        count_ = 0;
    }

    /// Calls visit(id, slot) for every id (dense ids in increasing order, then the others).
    template <class Visit>
    void for_each(Visit&& visit) const {
        for (std::size_t id = 0; id < dense_.size(); ++id) {
            if (dense_[id] != kNoSlot) visit(static_cast<BoxId>(id), dense_[id]);
        }
        for (const auto& [id, slot] : sparse_) visit(id, slot);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        // unordered_map: one pointer per bucket (none allocated while there is a single one,
        // kept inside the map) and one node per element holding the next pointer and the
        // (key, value) pair; libstdc++ caches no hash code in the node for integer keys.
        constexpr std::size_t node_bytes = sizeof(void*) + sizeof(std::pair<const BoxId, Slot>);
        const std::size_t buckets = sparse_.bucket_count() > 1 ? sparse_.bucket_count() : 0;
        return dense_.capacity() * sizeof(Slot) + buckets * sizeof(void*) + sparse_.size() * node_bytes;
    }

private:
    /// Ids below this go to the array when there are `count` boxes: at most two entries per box
    /// (plus a small start), so that sparse ids cannot blow the array up.
    static std::size_t dense_limit(std::size_t count) noexcept { return 2 * count + 1024; }

    void grow_dense(BoxId id) {
        // Doubling (up to the limit): ids arriving one by one grow the array, and move the hash
        // map's ids, a logarithmic number of times.
        const std::size_t doubled = std::max<std::size_t>(2 * dense_.size(), 64);
        resize_dense(std::max<std::size_t>(id + 1, std::min(doubled, dense_limit(count_ + 1))));
    }

    void resize_dense(std::size_t size) {
        dense_.resize(size, kNoSlot);
        // Ids of the hash map that the array now covers move to it, so that lookups of the
        // common (dense) ids never touch the map.
        for (auto it = sparse_.begin(); it != sparse_.end();) {
            if (it->first < dense_.size()) {
                dense_[it->first] = it->second;
                it = sparse_.erase(it);
            } else {
                ++it;
            }
        }
    }

    BulkVector<Slot> dense_;                  // dense_[id]: the slot of a small id, or kNoSlot
    std::unordered_map<BoxId, Slot> sparse_;  // the other ids
    std::size_t count_ = 0;
};

}  // namespace smb::detail
