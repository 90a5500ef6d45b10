// SPDX-License-Identifier: MIT
// The singular-item regrouping (src/paper/singular_regroup.hpp) on random lists: every item lands in
// its parent's section, normal items keep their order, arrivals come in sorted.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "paper/singular_regroup.hpp"

namespace smb::detail {
namespace {

TEST(SingularRegroup, RandomSectionsAndArrivals) {
    for (std::uint64_t seed = 1; seed <= 50; ++seed) {
        std::mt19937_64 rng(seed);
        const std::size_t parents = 50 + rng() % 200;
        const std::size_t old_sections = 1 + rng() % 8;
        const std::size_t new_sections = 1 + rng() % 8;
        std::vector<SegmentId> parent_segment(parents + 20);
        for (auto& s : parent_segment) s = static_cast<SegmentId>(rng() % new_sections);
        // The list: items 0 .. 2*parents-1 spread over the old sections, arrivals after them.
        std::vector<std::vector<AxisEntry<double>>> by_old(old_sections);
        std::uniform_real_distribution<double> key(0, 10);
        for (Item item = 0; item < 2 * parents; ++item) by_old[rng() % old_sections].push_back({key(rng), item});
        std::vector<AxisEntry<double>> list;
        std::vector<std::uint32_t> old_begin{0};
        for (const auto& section : by_old) {
            list.insert(list.end(), section.begin(), section.end());
            old_begin.push_back(static_cast<std::uint32_t>(list.size()));
        }
        std::vector<AxisEntry<double>> arrivals;
        for (Item item = static_cast<Item>(2 * parents); item < 2 * (parents + 20); ++item)
            arrivals.push_back({key(rng), item});
        std::vector<std::uint32_t> counts(new_sections + 1, 0);
        for (const auto& e : list) ++counts[parent_segment[e.item >> 1] + 1];
        for (const auto& e : arrivals) ++counts[parent_segment[e.item >> 1] + 1];
        for (std::size_t j = 0; j < new_sections; ++j) counts[j + 1] += counts[j];

        std::vector<AxisEntry<double>> out = list;
        RegroupScratch<double> scratch;
        regroup_by_parent_segment<double>(out, old_begin, arrivals, parent_segment, counts, scratch);

        ASSERT_EQ(out.size(), list.size() + arrivals.size()) << "seed " << seed;
        for (std::size_t j = 0; j < new_sections; ++j) {
            std::vector<Item> normal_expected;
            if (j < old_sections) {
                for (std::uint32_t i = old_begin[j]; i < old_begin[j + 1]; ++i) {
                    if (parent_segment[list[i].item >> 1] == j) normal_expected.push_back(list[i].item);
                }
            }
            std::vector<Item> normal_got;
            std::vector<AxisEntry<double>> moved;
            for (std::uint32_t i = counts[j]; i < counts[j + 1]; ++i) {
                ASSERT_EQ(parent_segment[out[i].item >> 1], j) << "seed " << seed;
                const bool was_here =
                    j < old_sections && std::any_of(list.begin() + old_begin[j], list.begin() + old_begin[j + 1],
                                                    [&](const auto& e) { return e.item == out[i].item; });
                if (was_here)
                    normal_got.push_back(out[i].item);
                else
                    moved.push_back(out[i]);
            }
            EXPECT_EQ(normal_got, normal_expected) << "seed " << seed << " section " << j;
            EXPECT_TRUE(std::is_sorted(moved.begin(), moved.end(), entry_less<double>)) << "seed " << seed;
        }
    }
}

}  // namespace
}  // namespace smb::detail
