// SPDX-License-Identifier: MIT
#pragma once
// What a rank sent to the regions at its last step: each of its boxes, in id order, and the
// regions it went to. Against it, a step sends only what changed (docs/distributed.md).

#include <cstddef>
#include <span>
#include <vector>

#include "smb/pair.hpp"

namespace smb::mpi::detail {

template <class Box>
struct SentBoxes {
    std::vector<BoxId> ids;  ///< increasing
    std::vector<Box> boxes;
    std::vector<std::size_t> first{0};  ///< box i went to regions[first[i] .. first[i + 1])
    std::vector<int> regions;

    [[nodiscard]] std::size_t size() const noexcept { return ids.size(); }
    [[nodiscard]] std::span<const int> regions_of(std::size_t i) const noexcept {
        return std::span<const int>(regions).subspan(first[i], first[i + 1] - first[i]);
    }
    void clear() {
        ids.clear();
        boxes.clear();
        first.assign(1, 0);
        regions.clear();
    }
    void add(BoxId id, const Box& box, std::span<const int> to) {
        ids.push_back(id);
        boxes.push_back(box);
        regions.insert(regions.end(), to.begin(), to.end());
        first.push_back(regions.size());
    }
};

}  // namespace smb::mpi::detail
