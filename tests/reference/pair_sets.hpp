// SPDX-License-Identifier: MIT
#pragma once
// The reference for pair events: a span of pairs as a vector, and the set difference of two
// lists in any order, sorted by (a, b) as the events are.

#include <algorithm>
#include <iterator>
#include <span>
#include <vector>

#include "smb/pair.hpp"

namespace smb::test {

inline std::vector<Pair> as_vector(std::span<const Pair> pairs) { return {pairs.begin(), pairs.end()}; }

/// The pairs of `x` that are not in `y`, sorted.
inline std::vector<Pair> difference(std::vector<Pair> x, std::vector<Pair> y) {
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    std::vector<Pair> out;
    std::set_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(out));
    return out;
}

}  // namespace smb::test
