// SPDX-License-Identifier: MIT
#pragma once
// A World's query index and the state of its boxes it was built from. Only the box store's
// change count decides whether it is current: detections, filters and statics leave the boxes
// as they were, so the queries between two detections reuse one index.

#include <concepts>
#include <cstdint>

#include "smb/box_index.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
struct WorldQueryIndex {
    BoxIndex<Real, Dim> index;
    /// BoxStore::changes() when `index` was built; a store with no change is empty, as is a
    /// fresh index.
    std::uint64_t built_at = 0;
};

}  // namespace smb::detail
