// SPDX-License-Identifier: MIT
// The radix sort of pair keys (src/core/pair_key_sort.hpp), as smb::bullet calls it, against
// std::sort: keys of 2 to 62 bits (two to four passes), lists below and above the size where the
// radix sort takes over, keys that share digits (passes skipped), repeated keys.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "core/pair_key_sort.hpp"

namespace {

using smb::detail::sort_pair_keys;

std::vector<std::uint64_t> random_keys(std::size_t count, int bits, std::uint64_t shared, std::mt19937_64& random) {
    const std::uint64_t mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
    std::vector<std::uint64_t> keys(count);
    for (std::uint64_t& key : keys) key = ((random() & mask) & ~shared) | (shared & mask);
    return keys;
}

TEST(BulletPairKeys, SortsAsStdSortDoes) {
    std::mt19937_64 random(7);
    std::vector<std::uint64_t> spare;
    std::vector<std::uint32_t> counts;
    for (const int bits : {2, 11, 16, 17, 28, 34, 40, 48, 62}) {
        for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2047}, std::size_t{2048},
                                        std::size_t{5000}, std::size_t{70000}}) {
            // No digit shared, then the low bits and a middle band the same in every key.
            for (const std::uint64_t shared : {std::uint64_t{0}, std::uint64_t{0xffff}, std::uint64_t{0xff0000ff00}}) {
                std::vector<std::uint64_t> keys = random_keys(count, bits, shared, random);
                std::vector<std::uint64_t> expected = keys;
                std::sort(expected.begin(), expected.end());
                sort_pair_keys(keys, bits, spare, counts);
                ASSERT_EQ(keys, expected) << bits << " bits, " << count << " keys, shared " << shared;
            }
        }
    }
}

TEST(BulletPairKeys, RepeatedAndAlreadySortedKeys) {
    std::vector<std::uint64_t> spare;
    std::vector<std::uint32_t> counts;
    std::vector<std::uint64_t> keys(10000);
    for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = (i * 7919) % 101;  // 101 values, each ~99 times
    std::vector<std::uint64_t> expected = keys;
    std::sort(expected.begin(), expected.end());
    sort_pair_keys(keys, 7, spare, counts);
    EXPECT_EQ(keys, expected);
    sort_pair_keys(keys, 7, spare, counts);  // sorted already
    EXPECT_EQ(keys, expected);
    std::vector<std::uint64_t> same(4000, 12345);
    sort_pair_keys(same, 14, spare, counts);
    EXPECT_EQ(same, std::vector<std::uint64_t>(4000, 12345));
}

}  // namespace
