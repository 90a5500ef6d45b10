// SPDX-License-Identifier: MIT
#pragma once

#include <algorithm>
#include <compare>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace smb {

/// Caller-chosen identifier of a box in a World: any unsigned 64-bit value.
using BoxId = std::uint64_t;

/// One overlapping pair of boxes, always with a < b.
struct Pair {
    BoxId a = 0;
    BoxId b = 0;

    friend auto operator<=>(const Pair&, const Pair&) = default;
};

/// Puts pairs in (a, b) order: the order of the pair CSV. detect() itself reports pairs in a
/// deterministic but unspecified order, so callers who need a canonical list sort it.
inline void sort_pairs(std::vector<Pair>& pairs) { std::sort(pairs.begin(), pairs.end()); }

/// Receives the pairs of one detection in chunks, so that a caller can consume billions of
/// pairs without holding them all.
using PairSink = std::function<void(std::span<const Pair>)>;

}  // namespace smb
