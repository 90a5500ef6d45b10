// SPDX-License-Identifier: MIT
// The one-shot entry point: box i has id i, pairs as brute force finds them.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <list>
#include <span>
#include <string>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

template <typename WorldType>
class FindOverlappingPairsTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;

    static ::testing::AssertionResult finds_like_brute_force(const std::vector<BoxT>& boxes,
                                                             const WorldSettings& settings = test_settings()) {
        const std::span<const BoxT> view(boxes);
        const std::vector<Pair> pairs = find_overlapping_pairs<Real, Dim>(view, settings);
        return same_pairs(pairs, brute_force_pairs<Real, Dim>(view), [&boxes](BoxId id) {
            return id < boxes.size() ? describe(boxes[id]) : std::string("<out of range>");
        });
    }

    static std::vector<BoxT> random_boxes(std::uint64_t seed, std::size_t count, double space, double min_side,
                                          double max_side) {
        Random random(seed);
        std::vector<BoxT> boxes;
        for (std::size_t i = 0; i < count; ++i)
            boxes.push_back(random_box<Real, Dim>(random, 0, space, min_side, max_side));
        return boxes;
    }
};

TYPED_TEST_SUITE(FindOverlappingPairsTest, WorldTypes, WorldTypeNames);

TYPED_TEST(FindOverlappingPairsTest, NoBoxes) {
    const std::vector<typename TestFixture::BoxT> none;
    EXPECT_TRUE((find_overlapping_pairs<typename TestFixture::Real, TestFixture::Dim>(
                     std::span<const typename TestFixture::BoxT>(none)))
                    .empty());
}

TYPED_TEST(FindOverlappingPairsTest, OneBox) {
    const std::vector<typename TestFixture::BoxT> one(1);
    EXPECT_TRUE(this->finds_like_brute_force(one));
}

TYPED_TEST(FindOverlappingPairsTest, RandomScenesOfSeveralDensities) {
    std::uint64_t seed = 300;
    for (const double space : {8.0, 20.0, 60.0, 400.0}) {
        SCOPED_TRACE(::testing::Message() << "space " << space << ", seed " << seed);
        EXPECT_TRUE(this->finds_like_brute_force(this->random_boxes(seed++, scaled(1500), space, 0.2, 2.0)));
    }
}

TYPED_TEST(FindOverlappingPairsTest, IdenticalAndDegenerateBoxes) {
    std::vector<typename TestFixture::BoxT> boxes(100);  // all the point at the origin
    auto more = this->random_boxes(311, 200, 3.0, 0.0, 0.5);
    boxes.insert(boxes.end(), more.begin(), more.end());
    EXPECT_TRUE(this->finds_like_brute_force(boxes));
}

TYPED_TEST(FindOverlappingPairsTest, OneHugeBoxAmongSmallOnes) {
    auto boxes = this->random_boxes(321, scaled(1000), 100.0, 0.1, 1.0);
    Random random(322);
    boxes[boxes.size() / 2] = random_box<typename TestFixture::Real, TestFixture::Dim>(random, 50, 50, 80, 80);
    EXPECT_TRUE(this->finds_like_brute_force(boxes));
}

TYPED_TEST(FindOverlappingPairsTest, SettingsDoNotChangeTheAnswer) {
    const auto boxes = this->random_boxes(331, scaled(800), 25.0, 0.3, 2.0);
    for (const std::size_t population : {std::size_t{1}, std::size_t{3}, std::size_t{64}, std::size_t{100000}}) {
        SCOPED_TRACE(::testing::Message() << "target_cell_population " << population);
        WorldSettings settings = test_settings();
        settings.target_cell_population = population;
        settings.pair_chunk_size = 1;
        EXPECT_TRUE(this->finds_like_brute_force(boxes, settings));
    }
}

// Every contiguous range of boxes is taken as it is: no explicit std::span<const Box> needed.
TYPED_TEST(FindOverlappingPairsTest, TakesEveryContiguousRangeOfBoxes) {
    std::vector<typename TestFixture::BoxT> boxes = this->random_boxes(341, 300, 12.0, 0.3, 2.0);
    const std::vector<Pair> expected = find_overlapping_pairs<typename TestFixture::Real, TestFixture::Dim>(
        std::span<const typename TestFixture::BoxT>(boxes));
    ASSERT_FALSE(expected.empty());
    const std::vector<typename TestFixture::BoxT>& const_boxes = boxes;
    const std::span<typename TestFixture::BoxT> mutable_span(boxes);
    const std::span<const typename TestFixture::BoxT> const_span(boxes);
    std::array<typename TestFixture::BoxT, 300> array{};
    std::copy(boxes.begin(), boxes.end(), array.begin());

    EXPECT_EQ(find_overlapping_pairs(boxes), expected);
    EXPECT_EQ(find_overlapping_pairs(const_boxes), expected);
    EXPECT_EQ(find_overlapping_pairs(std::span(boxes)), expected);
    EXPECT_EQ(find_overlapping_pairs(mutable_span), expected);
    EXPECT_EQ(find_overlapping_pairs(const_span), expected);
    EXPECT_EQ(find_overlapping_pairs(array), expected);
    std::vector<Pair> with_settings = find_overlapping_pairs(boxes, test_settings());
    std::vector<Pair> sorted_expected = expected;
    sort_pairs(with_settings);
    sort_pairs(sorted_expected);
    EXPECT_EQ(with_settings, sorted_expected);
    EXPECT_TRUE(find_overlapping_pairs(std::vector<typename TestFixture::BoxT>{}).empty());
}

// What is not a contiguous range of smb boxes does not reach find_overlapping_pairs.
static_assert(BoxRange<std::vector<Box3d>> && BoxRange<std::span<Box2f>> && BoxRange<std::array<Box3f, 2>>);
static_assert(BoxRange<const std::vector<Box2d>> && BoxRange<Box3d[4]>);
static_assert(!BoxRange<std::vector<double>> && !BoxRange<std::list<Box3d>> && !BoxRange<Box3d>);

}  // namespace
}  // namespace smb::test
