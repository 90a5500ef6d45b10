// SPDX-License-Identifier: MIT
// Pairs sorted as keys (src/core/pair_key_sort.hpp), as the events call it, against std::sort:
// names of 1 to 32 bits (keys up to 64 bits), names too wide for a key (the comparison sort),
// lists below and above the size where the radix sort takes over, repeated pairs, and one
// scratch reused across all of them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "core/pair_key_sort.hpp"
#include "smb/pair.hpp"

namespace {

using smb::BoxId;
using smb::Pair;

std::vector<Pair> random_pairs(std::size_t count, int name_bits, std::mt19937_64& random) {
    const BoxId mask = name_bits >= 64 ? ~BoxId{0} : (BoxId{1} << name_bits) - 1;
    std::vector<Pair> pairs(count);
    for (Pair& pair : pairs) {
        BoxId a = random() & mask;
        BoxId b = random() & mask;
        if (a == b) b = a == 0 ? 1 : a - 1;
        pair = Pair{std::min(a, b), std::max(a, b)};
    }
    return pairs;
}

TEST(PairKeySort, SortsPairsAsStdSortDoes) {
    std::mt19937_64 random(11);
    smb::detail::PairSortScratch scratch;
    for (const int bits : {1, 2, 12, 20, 31, 32, 33, 48, 64}) {
        for (const std::size_t count :
             {std::size_t{0}, std::size_t{1}, std::size_t{2047}, std::size_t{2048}, std::size_t{40000}}) {
            std::vector<Pair> pairs = random_pairs(count, bits, random);
            std::vector<Pair> expected = pairs;
            std::sort(expected.begin(), expected.end());
            smb::detail::sort_pairs_fast(pairs, scratch);
            ASSERT_EQ(pairs, expected) << bits << "-bit names, " << count << " pairs";
        }
    }
}

TEST(PairKeySort, RepeatedPairsAndSortedInput) {
    smb::detail::PairSortScratch scratch;
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < 20000; ++i) pairs.push_back(Pair{(i * 7919) % 97, 97 + (i * 31) % 13});
    std::vector<Pair> expected = pairs;
    std::sort(expected.begin(), expected.end());
    smb::detail::sort_pairs_fast(pairs, scratch);
    EXPECT_EQ(pairs, expected);
    smb::detail::sort_pairs_fast(pairs, scratch);  // sorted already
    EXPECT_EQ(pairs, expected);
    EXPECT_GT(scratch.bytes_held(), 0U);
}

}  // namespace
