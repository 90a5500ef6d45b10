// SPDX-License-Identifier: MIT
#pragma once
// The obviously correct reference every smb test compares against: all pairs, one by one.

#include <algorithm>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::test {

/// Every overlapping pair among `boxes` (box i under `ids[i]`), closed overlap as in
/// smb::overlaps, each pair once with a < b, sorted by (a, b). O(n^2) on purpose.
template <std::floating_point Real, int Dim>
std::vector<Pair> brute_force_pairs(std::span<const BoxId> ids, std::span<const Box<Real, Dim>> boxes) {
    if (ids.size() != boxes.size()) throw std::invalid_argument("brute_force_pairs: length mismatch");
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < boxes.size(); ++j) {
            if (!overlaps(boxes[i], boxes[j])) continue;
            const BoxId a = std::min(ids[i], ids[j]);
            const BoxId b = std::max(ids[i], ids[j]);
            pairs.push_back({a, b});
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

/// Box i has id i, as in World::assign and find_overlapping_pairs.
template <std::floating_point Real, int Dim>
std::vector<Pair> brute_force_pairs(std::span<const Box<Real, Dim>> boxes) {
    std::vector<BoxId> ids(boxes.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<BoxId>(i);
    return brute_force_pairs<Real, Dim>(ids, boxes);
}

}  // namespace smb::test
