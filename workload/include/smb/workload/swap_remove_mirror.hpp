// SPDX-License-Identifier: MIT
#pragma once
// The array an array-based simulation keeps for smb::Detector, built from a scene kept in
// increasing id order (the paper's environment, the benchmark scenes): a body keeps its index
// while it lives, a removed body's index goes to the last body (swap-remove), new bodies are
// appended. The scene's own arrays close up in id order instead, which shifts the index of every
// body after a removed one; a Detector fed those would see most bodies change index at every step
// that removes one.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::workload {

template <class BoxType>
class SwapRemoveMirror {
public:
    using box_type = BoxType;

    /// Follows one step of the scene: `removed_ids` gone, `inserted_ids` new, and `env_ids` with
    /// `boxes` every box after the step, in increasing id order. Removals first, then every box
    /// copied to its body's index.
    void follow(std::span<const BoxId> removed_ids, std::span<const BoxId> inserted_ids, std::span<const BoxId> env_ids,
                std::span<const box_type> boxes) {
        // Before this step, environment index i held the body now at index index_of_[i] here,
        // and env_ids_ held the environment's ids in its (increasing) order.
        swaps_.clear();
        for (const BoxId removed : removed_ids) {
            const auto at = std::lower_bound(env_ids_.begin(), env_ids_.end(), removed);
            const auto env_index = static_cast<std::size_t>(at - env_ids_.begin());
            const std::uint32_t slot = index_of_[env_index];
            const auto last = static_cast<std::uint32_t>(ids_.size() - 1);
            swaps_.push_back({slot, last});
            // The last body takes the freed index.
            index_of_[env_of_index_[last]] = slot;
            env_of_index_[slot] = env_of_index_[last];
            ids_[slot] = ids_[last];
            ids_.pop_back();
            env_of_index_.pop_back();
            index_of_[env_index] = kGone;
        }
        // Survivors keep their order in the environment's arrays; new bodies come after them.
        std::size_t kept = 0;
        for (const std::uint32_t index : index_of_) {
            if (index != kGone) index_of_[kept++] = index;
        }
        index_of_.resize(kept);
        for (std::size_t i = 0; i < inserted_ids.size(); ++i) {
            index_of_.push_back(static_cast<std::uint32_t>(ids_.size()));
            ids_.push_back(inserted_ids[i]);
            env_of_index_.push_back(0);
        }
        boxes_.resize(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            boxes_[index_of_[i]] = boxes[i];
            env_of_index_[index_of_[i]] = static_cast<std::uint32_t>(i);
        }
        env_ids_.assign(env_ids.begin(), env_ids.end());
    }

    /// Renumbers the bodies: index i now holds the body that was at index order[i] (a
    /// permutation of every index). The swap-removes of the last follow() are forgotten: they
    /// name indices from before.
    void renumber(std::span<const std::uint32_t> order) {
        swaps_.clear();
        std::vector<box_type> boxes(order.size());
        std::vector<BoxId> ids(order.size());
        std::vector<std::uint32_t> env_of_index(order.size());
        for (std::size_t i = 0; i < order.size(); ++i) {
            boxes[i] = boxes_[order[i]];
            ids[i] = ids_[order[i]];
            env_of_index[i] = env_of_index_[order[i]];
            index_of_[env_of_index[i]] = static_cast<std::uint32_t>(i);
        }
        boxes_.swap(boxes);
        ids_.swap(ids);
        env_of_index_.swap(env_of_index);
    }

    [[nodiscard]] std::span<const box_type> boxes() const noexcept { return boxes_; }
    [[nodiscard]] BoxId id_at(std::size_t index) const noexcept { return ids_[index]; }
    /// The id of the body at every index.
    [[nodiscard]] std::span<const BoxId> ids() const noexcept { return ids_; }
    /// The swap-removes of the last follow(), in order: (removed index, last index), as
    /// smb::PairEvents::swap_remove takes them.
    [[nodiscard]] std::span<const std::pair<std::uint32_t, std::uint32_t>> swaps() const noexcept { return swaps_; }

private:
    static constexpr std::uint32_t kGone = 0xFFFFFFFFU;
    std::vector<box_type> boxes_;
    std::vector<BoxId> ids_;                   // per index
    std::vector<std::uint32_t> env_of_index_;  // per index: the environment's index of its body
    std::vector<std::uint32_t> index_of_;      // per environment index: the body's index here
    std::vector<BoxId> env_ids_;               // the environment's ids, in its order
    std::vector<std::pair<std::uint32_t, std::uint32_t>> swaps_;
};

}  // namespace smb::workload
