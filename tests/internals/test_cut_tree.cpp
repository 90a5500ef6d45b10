// SPDX-License-Identifier: MIT
// The persistent cut planes (src/cuts/cut_tree.hpp): equal-count cuts, exact on small groups and
// from an evenly spaced sample on large ones, and the location of values against them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "cuts/cut_tree.hpp"

namespace smb::detail {
namespace {

std::vector<std::size_t> segment_counts(const CutTree<double, 2>& tree, const std::vector<double>& keys) {
    std::vector<std::size_t> counts(tree.segments(0), 0);
    for (const double key : keys) ++counts[segment_of(tree.cuts(0, 0), key)];
    return counts;
}

TEST(CutTree, SmallGroupsAreCutAtTheExactQuantiles) {
    CutTree<double, 2> tree;
    tree.reshape(4);
    for (const std::size_t n : {std::size_t{400}, std::size_t{4000}}) {  // recursive selection, radix sort
        QuantileSelector<double> selector;
        for (std::size_t i = 0; i < n; ++i) selector.keys.push_back(static_cast<double>((i * 7919) % n));
        const std::vector<double> original = selector.keys;
        tree.cut(0, 0, selector);
        EXPECT_EQ(segment_counts(tree, original), std::vector<std::size_t>(4, n / 4));
    }
}

TEST(CutTree, LargeGroupsAreCutFromASampleWithinAFewPercentOfEven) {
    CutTree<double, 2> tree;
    tree.reshape(40);
    std::mt19937_64 random(7);
    std::normal_distribution<double> coordinate(0.0, 10.0);
    std::vector<double> keys(1000000);
    for (double& key : keys) key = coordinate(random);
    QuantileSelector<double> scratch;
    tree.cut_group(
        0, 0, keys.size(), [&](std::size_t i) { return keys[i]; }, scratch);
    EXPECT_EQ(scratch.keys.size(), (CutTree<double, 2>::kSamplePerSegment * 40));
    const auto counts = segment_counts(tree, keys);
    const double even = static_cast<double>(keys.size()) / 40.0;
    for (const std::size_t count : counts) {
        EXPECT_GT(static_cast<double>(count), 0.75 * even);
        EXPECT_LT(static_cast<double>(count), 1.25 * even);
    }
    EXPECT_TRUE(std::is_sorted(tree.cuts(0, 0).begin(), tree.cuts(0, 0).end()));
}

TEST(CutTree, EqualKeysShareASegment) {
    CutTree<double, 2> tree;
    tree.reshape(8);
    std::vector<double> keys(100000, 3.0);
    for (std::size_t i = 0; i < 1000; ++i) keys[i * 100] = static_cast<double>(i);
    QuantileSelector<double> scratch;
    // The group is sampled (100000 keys, 8 segments).
    tree.cut_group(
        0, 0, keys.size(), [&](std::size_t i) { return keys[i]; }, scratch);
    const auto planes = tree.cuts(0, 0);
    const std::uint32_t of_three = segment_of(planes, 3.0);
    // Every key 3.0 is in one segment, whatever the planes.
    for (const double key : keys) {
        if (key == 3.0) {
            EXPECT_EQ(segment_of(planes, key), of_three);
        }
    }
}

TEST(CutTree, PlanesStayATypicalExtentApartSoThatALayerOfBoxesIsNotOversized) {
    // 2000 unit boxes in a layer four boxes deep, cut into 16 segments: equal counts alone put
    // the planes a quarter box apart, so nearly every box would span more than two segments.
    CutTree<float, 2> tree;
    tree.reshape(16);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<float> low(0.0F, 3.0F);
    std::vector<float> mins(2000);
    for (float& min : mins) min = low(random);
    QuantileSelector<float> scratch;
    tree.cut_group(
        1, 0, mins.size(), [&](std::size_t i) { return mins[i]; }, [](std::size_t) { return 1.0F; }, scratch);
    const std::span<const float> planes = tree.cuts(1, 0);
    ASSERT_TRUE(std::is_sorted(planes.begin(), planes.end()));
    std::size_t finite = 0;
    for (std::size_t j = 0; j < planes.size(); ++j) {
        if (!std::isfinite(planes[j])) {
            EXPECT_EQ(planes[j], std::numeric_limits<float>::infinity());
            continue;
        }
        ++finite;
        if (j > 0) {
            EXPECT_GE(planes[j] - planes[j - 1], 1.0F);
        }
    }
    EXPECT_GE(finite, 2U);
    EXPECT_LE(finite, 3U);
    for (const float min : mins) {
        const std::uint32_t lo = segment_of(planes, min);
        EXPECT_LE(segment_of_max(planes, min + 1.0F, lo) - lo, 1U) << "min " << min;
    }
    // Without extents (or with boxes small against the segments) the planes are the quantiles.
    tree.cut_group(
        1, 0, mins.size(), [&](std::size_t i) { return mins[i]; }, scratch);
    EXPECT_TRUE(std::all_of(planes.begin(), planes.end(), [](float plane) { return std::isfinite(plane); }));
}

TEST(CutTree, SegmentNearAgreesWithSegmentOf) {
    std::vector<double> planes;
    for (int i = 0; i < 100; ++i) planes.push_back(i * 1.5);
    std::mt19937_64 random(3);
    std::uniform_real_distribution<double> value(-10.0, 160.0);
    for (int trial = 0; trial < 10000; ++trial) {
        const double v = trial % 50 == 0 ? planes[trial % planes.size()] : value(random);
        const auto hint = static_cast<std::uint32_t>(random() % 102);
        const std::uint32_t found = segment_of(std::span<const double>(planes), v);
        std::size_t misses = 0;
        ASSERT_EQ(segment_near(std::span<const double>(planes), v, hint, misses), found);
        // A search only where the hint was more than one segment off (or no segment at all).
        const bool off = hint > planes.size() || found + 1 < hint || found > hint + 1;
        ASSERT_EQ(misses, off ? 1U : 0U) << "hint " << hint << ", segment " << found;
        ASSERT_EQ(segment_of(std::span<const double>(planes).first(40), v),
                  static_cast<std::uint32_t>(
                      std::count_if(planes.begin(), planes.begin() + 40, [&](double p) { return p <= v; })));
    }
}

TEST(CutTree, SegmentNearTakesTheHintOrASegmentBesideItWithoutASearch) {
    const std::vector<double> planes{1.0, 2.0, 3.0, 4.0};
    const std::span<const double> cuts(planes);
    std::size_t misses = 0;
    EXPECT_EQ(segment_near(cuts, 2.5, 2, misses), 2U);
    EXPECT_EQ(segment_near(cuts, 3.0, 2, misses), 3U) << "a plane belongs to the segment above it";
    EXPECT_EQ(segment_near(cuts, 1.5, 2, misses), 1U);
    EXPECT_EQ(segment_near(cuts, -7.0, 1, misses), 0U);
    EXPECT_EQ(segment_near(cuts, 9.0, 3, misses), 4U);
    EXPECT_EQ(segment_near(cuts, 9.0, 4, misses), 4U);
    EXPECT_EQ(misses, 0U);
    EXPECT_EQ(segment_near(cuts, 0.5, 2, misses), 0U);
    EXPECT_EQ(segment_near(cuts, 4.5, 2, misses), 4U);
    EXPECT_EQ(misses, 2U) << "two segments away needs the search";
}

TEST(CutTree, SegmentOfMaxIsTheMaxSegmentUpToTwoPastTheMin) {
    std::mt19937_64 random(5);
    for (const std::uint32_t k : {1U, 2U, 3U, 4U, 41U, 101U}) {
        CutTree<float, 2> tree;
        tree.reshape(k);
        for (std::size_t group = 0; group < tree.groups(1); ++group) {
            QuantileSelector<float> selector;
            for (std::uint32_t i = 0; i < 4 * k; ++i)
                selector.keys.push_back(static_cast<float>((i * 37 + group) % (4 * k)));
            tree.cut(1, group, selector);
        }
        std::uniform_real_distribution<float> value(-3.0F, static_cast<float>(4 * k) + 3.0F);
        for (int trial = 0; trial < 5000; ++trial) {
            const std::size_t group = random() % tree.groups(1);
            const std::span<const float> cuts = tree.cuts(1, group);
            float min = value(random);
            float max = value(random);
            if (trial % 7 == 0 && !cuts.empty()) min = cuts[random() % cuts.size()];  // on a plane
            if (trial % 11 == 0) max = min;                                           // a point
            if (trial % 13 == 0) max = std::numeric_limits<float>::infinity();
            if (max < min) std::swap(min, max);
            const std::uint32_t lo = segment_of(cuts, min);
            const std::uint32_t expected = std::min(segment_of(cuts, max), lo + 2);
            ASSERT_EQ(segment_of_max(cuts, max, lo), expected)
                << "k " << k << ", group " << group << ", min " << min << ", max " << max;
        }
    }
}

}  // namespace
}  // namespace smb::detail
