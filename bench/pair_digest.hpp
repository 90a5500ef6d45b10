// SPDX-License-Identifier: MIT
#pragma once
// A fingerprint of one step's pair set, so that methods run in separate processes can be
// compared exactly without writing millions of pairs to disk.

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "smb/pair.hpp"

namespace smb::bench {

/// Sorts `pairs` and hashes the sorted list. Throws std::logic_error if a pair has a >= b or
/// appears twice: a method must report each pair exactly once.
inline std::uint64_t digest_pairs(std::vector<Pair>& pairs) {
    std::sort(pairs.begin(), pairs.end());
    // Every word goes through the splitmix64 finalizer, so any differing bit of any id
    // changes every bit of the result.
    std::uint64_t hash = 0x9e3779b97f4a7c15ull;
    auto absorb = [&hash](std::uint64_t word) {
        hash ^= word;
        hash ^= hash >> 30;
        hash *= 0xbf58476d1ce4e5b9ull;
        hash ^= hash >> 27;
        hash *= 0x94d049bb133111ebull;
        hash ^= hash >> 31;
    };
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (pairs[i].a >= pairs[i].b) throw std::logic_error("pair with a >= b");
        if (i > 0 && pairs[i] == pairs[i - 1]) throw std::logic_error("pair reported twice");
        absorb(pairs[i].a);
        absorb(pairs[i].b);
    }
    absorb(pairs.size());
    return hash;
}

}  // namespace smb::bench
