// SPDX-License-Identifier: MIT
// The axial cut (src/paper/axial_cut.hpp): equal counts, never between equal coordinates.

#include <gtest/gtest.h>

#include <vector>

#include "paper/axial_cut.hpp"

namespace smb::detail {
namespace {

struct CutResult {
    std::vector<SegmentId> segment_of;
    std::vector<std::uint32_t> begin;
};

CutResult cut(const std::vector<double>& keys, SegmentId segments) {
    std::vector<AxisEntry<double>> section(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) section[i] = {keys[i], static_cast<Item>(i)};
    CutResult result;
    result.segment_of.assign(keys.size(), ~SegmentId{0});
    cut_section<double>(section, 0, segments, 0, result.segment_of, result.begin);
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

}  // namespace
}  // namespace smb::detail
