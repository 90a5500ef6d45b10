// SPDX-License-Identifier: MIT
// The axial cut (src/paper/axial_cut.hpp): equal counts, never between equal coordinates, and
// with the paper's segment rule no segment shorter than asked.

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "paper/axial_cut.hpp"

namespace smb::detail {
namespace {

struct CutResult {
    std::vector<SegmentId> segment_of;
    std::vector<std::uint32_t> begin;
};

CutResult cut(const std::vector<double>& keys, SegmentId segments, double min_length = 0) {
    std::vector<AxisEntry<double>> section(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) section[i] = {keys[i], static_cast<Item>(i)};
    CutResult result;
    result.segment_of.assign(keys.size(), ~SegmentId{0});
    cut_section<double>(section, 0, segments, 0, result.segment_of, result.begin, min_length);
    return result;
}

TEST(AxialCut, EqualCountsOnDistinctValues) {
    std::vector<double> keys(200);
    for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = static_cast<double>(i);
    const auto result = cut(keys, 6);
    ASSERT_EQ(result.begin.size(), 6U);
    for (std::size_t s = 0; s + 1 < result.begin.size(); ++s) {
        const auto length = result.begin[s + 1] - result.begin[s];
        EXPECT_GE(length, 33U);
        EXPECT_LE(length, 34U);
    }
    for (std::size_t i = 1; i < keys.size(); ++i) EXPECT_LE(result.segment_of[i - 1], result.segment_of[i]);
}

TEST(AxialCut, NeverSplitsEqualCoordinates) {
    const std::vector<double> keys{0, 1, 1, 1, 1, 1, 1, 2, 3, 4, 5, 5};
    const auto result = cut(keys, 4);
    for (std::size_t i = 1; i < keys.size(); ++i) {
        if (keys[i] == keys[i - 1]) {
            EXPECT_EQ(result.segment_of[i], result.segment_of[i - 1]) << i;
        }
    }
}

TEST(AxialCut, AllEqualMakesOneSegmentAndEmptyOnesLast) {
    const std::vector<double> keys(50, 7.0);
    const auto result = cut(keys, 5);
    for (const SegmentId s : result.segment_of) EXPECT_EQ(s, 0U);
    for (std::size_t s = 1; s < result.begin.size(); ++s) EXPECT_EQ(result.begin[s], 50U);
}

TEST(AxialCut, LongRunLeavesNoEmptySegmentInTheMiddle) {
    // Half the items share one value (say, the min ends of identical boxes).
    std::vector<double> keys(100, 0.0);
    for (std::size_t i = 50; i < keys.size(); ++i) keys[i] = 1.0;
    const auto result = cut(keys, 6);
    EXPECT_EQ(result.segment_of.front(), 0U);
    EXPECT_EQ(result.segment_of.back(), 1U) << "the max ends go to the very next segment";
}

TEST(AxialCut, MinusZeroEqualsZero) {
    const std::vector<double> keys{-1, -0.0, 0.0, -0.0, 0.0, 1, 2, 3};
    const auto result = cut(keys, 4);
    EXPECT_EQ(result.segment_of[1], result.segment_of[4]);
}

TEST(AxialCut, MinimumLengthMakesLongerSegmentsAndEmptyOnesLast) {
    // 100 keys 0.1 apart (0 to 9.9) in 10 segments by count would be 1.0 long; at least 2.5 long
    // leaves 4 segments: [0, 2.5), [2.5, 5), [5, 7.5), [7.5, 9.9].
    std::vector<double> keys(100);
    for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = 0.1 * static_cast<double>(i);
    const auto result = cut(keys, 10, 2.5);
    ASSERT_EQ(result.begin.size(), 10U);
    std::size_t occupied = 0;
    for (std::size_t s = 0; s < result.begin.size(); ++s) {
        const std::uint32_t end = s + 1 < result.begin.size() ? result.begin[s + 1] : 100U;
        if (end == result.begin[s]) {
            EXPECT_EQ(end, 100U) << "an empty segment before the list's end";
            continue;
        }
        ++occupied;
        if (end < 100U) {
            EXPECT_GE(keys[end] - keys[result.begin[s]], 2.5 - 1e-9) << "segment " << s;
        }
    }
    EXPECT_EQ(occupied, 4U);
    for (std::size_t i = 1; i < keys.size(); ++i) EXPECT_LE(result.segment_of[i - 1], result.segment_of[i]);
}

TEST(AxialCut, MinimumLengthShorterThanTheCountsChangesNothing) {
    std::vector<double> keys(200);
    for (std::size_t i = 0; i < keys.size(); ++i) keys[i] = static_cast<double>(i);
    EXPECT_EQ(cut(keys, 6, 10.0).begin, cut(keys, 6).begin);
}

TEST(AxialCut, MinimumLengthBeyondTheSectionMakesOneSegment) {
    const std::vector<double> keys{-3, -1, 0, 2, 5, 8};
    for (const double length : {20.0, std::numeric_limits<double>::infinity()}) {
        const auto result = cut(keys, 3, length);
        for (const SegmentId s : result.segment_of) EXPECT_EQ(s, 0U);
    }
}

}  // namespace
}  // namespace smb::detail
