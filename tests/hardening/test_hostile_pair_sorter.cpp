// SPDX-License-Identifier: MIT
// The bounded-memory sort behind `smb pairs`: whatever the memory allowance, the pairs come out
// exactly sorted, each once, and a large frame spills to temporary files instead of memory.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "spilling_pair_sorter.hpp"

namespace smb::test {
namespace {

std::vector<Pair> random_pairs(std::size_t count, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_int_distribution<BoxId> id(0, 500);  // small range: many equal pairs
    std::vector<Pair> pairs(count);
    for (Pair& pair : pairs) {
        pair.a = id(random);
        pair.b = pair.a + 1 + id(random);
    }
    return pairs;
}

std::vector<Pair> sorted_through(io::SpillingPairSorter& sorter, const std::vector<Pair>& pairs, std::size_t chunk) {
    for (std::size_t first = 0; first < pairs.size(); first += chunk)
        sorter.add(std::span<const Pair>(pairs).subspan(first, std::min(chunk, pairs.size() - first)));
    std::vector<Pair> out;
    sorter.finish([&](std::span<const Pair> sorted) {
        EXPECT_FALSE(sorted.empty());
        out.insert(out.end(), sorted.begin(), sorted.end());
    });
    return out;
}

TEST(HostilePairSorter, EveryAllowanceGivesTheSortedList) {
    const auto pairs = random_pairs(10007, 3);
    auto expected = pairs;
    std::sort(expected.begin(), expected.end());
    for (const std::size_t allowance : {2u, 3u, 7u, 100u, 4096u, 10007u, 1000000u}) {
        io::SpillingPairSorter sorter(allowance);
        EXPECT_EQ(sorted_through(sorter, pairs, 613), expected) << "allowance " << allowance;
        EXPECT_EQ(sorter.runs_spilled() > 0, allowance < pairs.size()) << "allowance " << allowance;
    }
}

TEST(HostilePairSorter, FramesAfterASpillAreIndependent) {
    io::SpillingPairSorter sorter(50);
    const auto big = random_pairs(1000, 5);
    const auto small = random_pairs(10, 6);
    auto expected_big = big;
    auto expected_small = small;
    std::sort(expected_big.begin(), expected_big.end());
    std::sort(expected_small.begin(), expected_small.end());
    EXPECT_EQ(sorted_through(sorter, big, 64), expected_big);
    EXPECT_EQ(sorted_through(sorter, small, 3), expected_small);
    EXPECT_TRUE(sorted_through(sorter, {}, 1).empty());
    EXPECT_EQ(sorted_through(sorter, big, 1000), expected_big);
}

}  // namespace
}  // namespace smb::test
