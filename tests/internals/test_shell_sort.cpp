// SPDX-License-Identifier: MIT
// The diminishing increment sort (src/paper/shell_sort.hpp) and its adaptive increment rule.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "paper/shell_sort.hpp"

namespace smb::detail {
namespace {

std::vector<AxisEntry<double>> shuffled_entries(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> coordinate(0.0, 100.0);
    std::vector<AxisEntry<double>> list(n);
    for (std::size_t i = 0; i < n; ++i) list[i] = {std::floor(coordinate(rng)), static_cast<Item>(i)};
    return list;
}

bool sorted(const std::vector<AxisEntry<double>>& list) {
    return std::is_sorted(list.begin(), list.end(), entry_less<double>);
}

TEST(EntryOrder, MinEndComesFirstAtEqualCoordinates) {
    const AxisEntry<double> max_end{1.0, 3};  // odd item: a max end
    const AxisEntry<double> min_end{1.0, 8};  // even item: a min end
    EXPECT_TRUE(entry_less(min_end, max_end));
    EXPECT_FALSE(entry_less(max_end, min_end));
    const AxisEntry<double> negative_zero{-0.0, 2};
    const AxisEntry<double> positive_zero{0.0, 4};
    EXPECT_TRUE(entry_less(negative_zero, positive_zero)) << "equal keys fall back to the item id";
    EXPECT_FALSE(entry_less(positive_zero, negative_zero));
}

class DisIncrements : public ::testing::TestWithParam<int> {};

TEST_P(DisIncrements, SortsAnyPermutation) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        auto list = shuffled_entries(1000 + seed * 37, seed);
        auto expected = list;
        std::sort(expected.begin(), expected.end(), entry_less<double>);
        diminishing_increment_sort<double>(list, GetParam());
        ASSERT_TRUE(sorted(list)) << "seed " << seed;
        for (std::size_t i = 0; i < list.size(); ++i) ASSERT_EQ(list[i].item, expected[i].item);
    }
}

INSTANTIATE_TEST_SUITE_P(Shell, DisIncrements, ::testing::Values(1, 2, 3, 5, 8, 16));

TEST(Dis, AlmostSortedListCostsAboutOneMovePerDisplacement) {
    std::vector<AxisEntry<double>> list(10000);
    for (std::size_t i = 0; i < list.size(); ++i) list[i] = {static_cast<double>(i), static_cast<Item>(2 * i)};
    // By value: a list entry is packed, and a reference to its key would be misaligned.
    for (std::size_t i = 0; i + 1 < list.size(); i += 100) {
        const double key = list[i].key;
        list[i].key = list[i + 1].key;
        list[i + 1].key = key;
    }
    const DisWork work = diminishing_increment_sort<double>(list, 1);
    EXPECT_TRUE(sorted(list));
    EXPECT_EQ(work.fine_moves, 100U);
    EXPECT_FALSE(work.fell_back);
}

TEST(Dis, HeavyDisorderFallsBackToIntrosort) {
    auto list = shuffled_entries(20000, 7);
    const DisWork work = diminishing_increment_sort<double>(list, 1);
    EXPECT_TRUE(sorted(list));
    EXPECT_TRUE(work.fell_back) << "insertion sort on a random list must not run to n^2/4 moves";
    // The budget is checked after each insertion, and one insertion shifts at most n items.
    EXPECT_LE(work.moves(), 9 * list.size() + 64);
}

TEST(DisController, GrowsOnDisorderAndShrinksWhenCoarsePassesIdle) {
    DisController controller;
    EXPECT_EQ(controller.increments(), 1);
    controller.learn(DisWork{.items = 100, .coarse_moves = 0, .fine_moves = 500, .fell_back = false});
    EXPECT_EQ(controller.increments(), 2);
    controller.learn(DisWork{.items = 100, .coarse_moves = 0, .fine_moves = 0, .fell_back = true});
    EXPECT_EQ(controller.increments(), 3);
    controller.learn(DisWork{.items = 100, .coarse_moves = 50, .fine_moves = 10, .fell_back = false});
    EXPECT_EQ(controller.increments(), 3) << "coarse passes that move items are worth keeping";
    controller.learn(DisWork{.items = 100, .coarse_moves = 1, .fine_moves = 10, .fell_back = false});
    EXPECT_EQ(controller.increments(), 2);
}

}  // namespace
}  // namespace smb::detail
