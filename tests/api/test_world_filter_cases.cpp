// SPDX-License-Identifier: MIT
// World filters and static boxes on small scenes whose pairs are known: two sets as categories,
// statics through assign(), both pipelines handing over to the filtered path and back, the
// predicate, statics that never pair, slots compacted under the filtered path, statics spanning
// the double range, one filter for many ids, and bad input that changes nothing.
// tests/api/test_world_filters.cpp holds the randomized checks against a brute force.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "smb/filter.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// The two-set (bipartite) recipe: set A in category 1 with mask 2, set B in category 2 with
/// mask 1; only pairs across the sets are reported.
TEST(WorldFilters, TwoSetsAsCategoriesPairOnlyAcross) {
    World2d world;
    world.insert(1, Box2d{{0, 0}, {2, 2}});
    world.insert(2, Box2d{{1, 1}, {3, 3}});
    world.insert(3, Box2d{{1, 0}, {2, 1}});
    world.insert(4, Box2d{{9, 9}, {10, 10}});
    const std::vector<BoxId> a = {1, 2};
    const std::vector<BoxId> b = {3, 4};
    const std::vector<Filter> fa(2, Filter{1, 2});
    const std::vector<Filter> fb(2, Filter{2, 1});
    world.set_filter(a, fa);
    world.set_filter(b, fb);
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 3}, {2, 3}}));
}

TEST(WorldFilters, AssignSeesStaticsThatMovedOrLeft) {
    World2d world;
    std::vector<Box2d> boxes = {Box2d{{0, 0}, {1, 1}}, Box2d{{5, 5}, {6, 6}}, Box2d{{0.5, 0.5}, {2, 2}},
                                Box2d{{9, 9}, {10, 10}}};
    world.assign(boxes);
    const std::vector<BoxId> statics = {0, 1, 3};
    world.set_static(statics, true);
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 2}}));
    boxes[1] = Box2d{{1.5, 1.5}, {3, 3}};  // a static moves onto box 2
    world.assign(boxes);
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 2}, {1, 2}}));
    boxes[2] = Box2d{{9, 9}, {9.5, 9.5}};  // box 2 moves onto static 3, which assign() then drops
    boxes.pop_back();
    world.assign(boxes);
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
    EXPECT_TRUE(world.is_static(1));
    EXPECT_FALSE(world.contains(3));
}

/// Both pipelines: the filtered path takes over from either and hands back to it.
class WorldFiltersPipelines : public ::testing::TestWithParam<Pipeline> {};
INSTANTIATE_TEST_SUITE_P(BothPipelines, WorldFiltersPipelines,
                         ::testing::Values(Pipeline::persistent_cuts, Pipeline::paper_lists));

TEST_P(WorldFiltersPipelines, DefaultFiltersAgainReturnToTheDefaultDetection) {
    WorldSettings settings;
    settings.pipeline = GetParam();
    World3d world(settings);
    world.insert(1, Box3d{{0, 0, 0}, {1, 1, 1}});
    world.insert(2, Box3d{{1, 1, 1}, {2, 2, 2}});
    world.insert(3, Box3d{{0, 0, 0}, {2, 2, 2}});
    world.set_filter(1, Filter{2, 2});  // pairs with no default box
    world.set_static(3, true);
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{2, 3}}));
    world.set_filter(1, Filter{});
    world.set_static(3, false);
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 2}, {1, 3}, {2, 3}}));
    EXPECT_EQ(world.filter(1), Filter{});
    EXPECT_FALSE(world.is_static(3));
    // Removals and arrivals while each path runs, then back and forth once more.
    world.remove(2);
    world.insert(4, Box3d{{1.5, 1.5, 1.5}, {3, 3, 3}});
    world.set_static(4, true);
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 3}, {3, 4}}));
    world.remove(3);
    world.insert(5, Box3d{{0, 0, 0}, {0.5, 0.5, 0.5}});
    world.set_static(4, false);
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 5}}));
}

TEST(WorldFilters, PredicateSeesOrderedPairsThatPassTheBits) {
    World2f world;
    for (BoxId id = 0; id < 6; ++id) world.insert(10 - id, Box2f{{0, 0}, {1, 1}});
    world.set_filter(10, Filter{0, ~0u});  // pairs with nothing: never shown to the predicate
    std::size_t calls = 0;
    world.set_pair_predicate([&](BoxId a, BoxId b) {
        ++calls;
        EXPECT_LT(a, b);
        EXPECT_NE(a, 10u);
        EXPECT_NE(b, 10u);
        return b != 9;
    });
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_EQ(calls, 10u);  // the 5 boxes of non-zero filter pair 10 ways
    EXPECT_EQ(pairs.size(), 6u);
    world.set_pair_predicate({});
    world.detect(pairs);
    EXPECT_EQ(pairs.size(), 10u);
}

TEST(WorldFilters, UnknownIdsAndMismatchedSpansChangeNothing) {
    World3f world;
    world.insert(1, Box3f{{0, 0, 0}, {1, 1, 1}});
    world.insert(2, Box3f{{0, 0, 0}, {1, 1, 1}});
    EXPECT_THROW(world.set_filter(7, Filter{2, 2}), UnknownIdError);
    EXPECT_THROW(world.set_static(7, true), UnknownIdError);
    EXPECT_THROW((void)world.filter(7), UnknownIdError);
    EXPECT_THROW((void)world.is_static(7), UnknownIdError);
    const std::vector<BoxId> ids = {1, 7};
    const std::vector<Filter> filters = {Filter{0, 0}, Filter{0, 0}};
    EXPECT_THROW(world.set_filter(ids, filters), UnknownIdError);
    EXPECT_THROW(world.set_static(ids, true), UnknownIdError);
    EXPECT_THROW(world.set_filter(std::span(ids).first(1), filters), ArgumentError);
    EXPECT_EQ(world.filter(1), Filter{});
    EXPECT_FALSE(world.is_static(1));
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 2}}));
    const World3f moved_from = std::move(world);
    EXPECT_THROW((void)world.filter(1), UnknownIdError);  // NOLINT(bugprone-use-after-move)
}

TEST(WorldFilters, StaticsNeverPairAndUnmovedStaticsAreNotIndexedAgain) {
    World3d world;
    std::vector<BoxId> statics;
    for (BoxId id = 0; id < 50; ++id) {
        world.insert(id, Box3d{{0, 0, double(id)}, {10, 10, double(id) + 1}});  // a stack of slabs
        statics.push_back(id);
    }
    world.set_static(statics, true);
    world.insert(100, Box3d{{1, 1, 4.5}, {2, 2, 5.5}});
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{4, 100}, {5, 100}}));
    // Moving a little inside its fat box, then leaving it; then a static moves.
    for (const double z : {4.6, 4.7, 20.2}) {
        world.update(100, Box3d{{1, 1, z}, {2, 2, z + 1}});
        world.detect(pairs);
        sort_pairs(pairs);
        const auto low = static_cast<BoxId>(std::floor(z) - 1 + (z == std::floor(z) ? 0 : 1));
        EXPECT_EQ(pairs, (std::vector<Pair>{{low, 100}, {low + 1, 100}})) << z;
    }
    // Touching counts: faces shared exactly with the slabs below and above.
    world.update(100, Box3d{{1, 1, 30}, {2, 2, 31}});
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{29, 100}, {30, 100}, {31, 100}}));
    world.update(100, Box3d{{1, 1, std::nextafter(31.0, 32.0)}, {2, 2, 32}});
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{31, 100}, {32, 100}}));
    world.update(100, Box3d{{1, 1, 20.2}, {2, 2, 21.2}});
    world.update(20, Box3d{{0, 0, 60}, {10, 10, 61}});
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{21, 100}}));
    world.remove(21);
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
}

TEST(WorldFilters, FlagsChangedBeforeTheDefaultPathCompactsNameNoStaleSlot) {
    // Box 0 turns static and dynamic again while box 50, before it in the store, is removed; a
    // default detection compacts the store; a filter then engages the filtered path, which must
    // not revisit the slot numbers noted before the compaction.
    World2d world;
    world.insert(50, Box2d{{0, -2}, {0, -2}});
    world.insert(0, Box2d{{-2, -2}, {-2, -2}});
    world.set_static(0, true);
    world.remove(50);
    world.set_static(0, false);
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
    world.set_filter(0, Filter{1, 3});
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
    world.insert(7, Box2d{{-3, -3}, {-1, -1}});
    world.detect(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 7}}));
    world.set_filter(7, Filter{2, 2});
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
}

TEST(WorldFilters, StaticsSpanningAlmostAllOfDoubleStillPair) {
    // The statics' extent overflows a double: the grid must fall back to one cell on that axis.
    World3d world;
    const double huge = 1.5e308;
    world.insert(1, Box3d{{-huge, 0, 0}, {-huge / 2, 1, 1}});
    world.insert(2, Box3d{{huge / 2, 0, 0}, {huge, 1, 1}});
    world.insert(3, Box3d{{-1, -1, -1}, {1, 1, 1}});
    const std::vector<BoxId> statics = {1, 2, 3};
    world.set_static(statics, true);
    world.insert(10, Box3d{{-huge, 0.5, 0.5}, {-huge, 0.5, 0.5}});
    world.insert(11, Box3d{{huge, 0, 0}, {huge, 0, 0}});
    world.insert(12, Box3d{{0, 0, 0}, {0, 0, 0}});
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 10}, {2, 11}, {3, 12}}));
}

TEST(WorldFilters, OneFilterForManyIdsAllOrNothing) {
    World2d world;
    for (BoxId id = 0; id < 6; ++id) world.insert(id, Box2d{{0, 0}, {1, 1}});
    const std::vector<BoxId> debris = {1, 3, 5};
    world.set_filter(debris, Filter{4, ~4u});  // debris never meets debris
    for (BoxId id = 0; id < 6; ++id) EXPECT_EQ(world.filter(id), (id % 2 ? Filter{4, ~4u} : Filter{})) << id;
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    std::vector<Pair> expected;
    for (BoxId a = 0; a < 6; ++a) {
        for (BoxId b = a + 1; b < 6; ++b) {
            if (a % 2 == 0 || b % 2 == 0) expected.push_back({a, b});
        }
    }
    EXPECT_EQ(pairs, expected);
    // An unknown id among them: no filter changes.
    const std::vector<BoxId> with_unknown = {0, 2, 9};
    EXPECT_THROW(world.set_filter(with_unknown, Filter{8, 8}), UnknownIdError);
    for (BoxId id = 0; id < 6; ++id) EXPECT_EQ(world.filter(id), (id % 2 ? Filter{4, ~4u} : Filter{})) << id;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, expected);
}

}  // namespace
}  // namespace smb::test
