#pragma once
// The O(n^2) all-pairs test: obviously correct, the reference for small scenes.

#include <algorithm>
#include <concepts>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::workload {

/// Every pair of overlapping boxes (closed convention), box i under ids[i], in (a, b) order.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::vector<Pair> brute_force_pairs(std::span<const BoxId> ids,
                                                  std::span<const Box<Real, Dim>> boxes) {
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
            if (overlaps(boxes[i], boxes[j]))
                pairs.push_back({std::min(ids[i], ids[j]), std::max(ids[i], ids[j])});
        }
    }
    sort_pairs(pairs);
    return pairs;
}

}  // namespace smb::workload
