// SPDX-License-Identifier: MIT
// World filters and static boxes against brute force: random category and mask bits over many
// steps with motion, insertions, removals, teleports and filter changes; static boxes that later
// move, are removed or become dynamic; both together; a predicate; and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <vector>

#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/filter.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// What the world should hold: each id's box, filter and static flag.
template <std::floating_point Real, int Dim>
struct Entry {
    Box<Real, Dim> box;
    Filter filter;
    bool is_static = false;
};

template <std::floating_point Real, int Dim>
std::vector<Pair> expected_pairs(const std::map<BoxId, Entry<Real, Dim>>& entries, const PairPredicate& predicate) {
    std::vector<std::pair<BoxId, const Entry<Real, Dim>*>> all;
    for (const auto& [id, e] : entries) all.emplace_back(id, &e);
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < all.size(); ++i) {
        for (std::size_t j = i + 1; j < all.size(); ++j) {
            const auto& a = *all[i].second;
            const auto& b = *all[j].second;
            if (a.is_static && b.is_static) continue;
            if (!filters_pass(a.filter, b.filter) || !overlaps(a.box, b.box)) continue;
            if (predicate && !predicate(all[i].first, all[j].first)) continue;
            pairs.push_back({all[i].first, all[j].first});
        }
    }
    return pairs;
}

/// A random filter from a few bits, so that some pairs pass and some do not; now and then 0.
inline Filter random_filter(Random& random) {
    Filter f;
    f.category = static_cast<std::uint32_t>(uniform_index(random, 4));  // 0..3
    f.mask = static_cast<std::uint32_t>(uniform_index(random, 8));      // 0..7
    if (chance(random, 0.3)) f = Filter{};
    if (chance(random, 0.05)) f = Filter{f.category << 20, f.mask | (f.mask << 20)};  // past 16 bits
    return f;
}

/// A filter from values that split the boxes into interaction classes: two layers that ignore
/// each other ({1, 1}, {2, 2}), two sets that meet only across ({4, 8}, {8, 4}), a value that
/// meets nothing present ({16, 32}), one that meets only the first layer's {1, 65} boxes
/// ({64, 1}); now and then the default (which meets the first layer and the others of category 1)
/// or mask 0.
inline Filter layered_filter(Random& random) {
    static constexpr Filter kValues[] = {{1, 1}, {2, 2}, {4, 8}, {8, 4}, {16, 32}, {64, 1}, {1, 65}, {2, 0}};
    if (chance(random, 0.1)) return Filter{};
    return kValues[uniform_index(random, std::size(kValues))];
}

/// A filter from more values than the interaction classes keep apart (80, every one passing
/// with every other): the boxes are detected as one class.
inline Filter many_valued_filter(Random& random) {
    return Filter{static_cast<std::uint32_t>(1 | (uniform_index(random, 80) << 1)), 1};
}

enum class FilterValues { random, layered, many };

struct Scenario {
    bool filters = true;
    FilterValues values = FilterValues::random;
    double static_share = 0.0;  // boxes made static at the start
    bool predicate = false;
    int steps = 25;
    std::size_t count = 400;
    BoxId first_id = 0;  // from 2^32 on, the pipeline's keys cannot hold the ids
    double skin = 0;     // WorldSettings::skin
};

template <typename WorldType>
class WorldFiltersTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;

    void run(const Scenario& scenario, std::uint64_t seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Random random(seed);
        const std::size_t count = scaled(scenario.count);
        space_ = std::pow(static_cast<double>(count) * std::pow(1.5, Dim) / 0.35, 1.0 / Dim);
        WorldSettings settings = test_settings();
        settings.skin = scenario.skin;
        World<Real, Dim> world(settings);
        std::map<BoxId, Entry<Real, Dim>> entries;
        BoxId next = scenario.first_id;
        auto add = [&](BoxId id) {
            const BoxT box = random_box<Real, Dim>(random, 0, space_, 1.0, 2.0);
            world.insert(id, box);
            entries[id] = {box, Filter{}, false};
        };
        for (std::size_t i = 0; i < count; ++i) add(next++);
        PairPredicate predicate;
        if (scenario.predicate) {
            // Ids whose sum is divisible by 3 never pair: something the bits cannot say.
            predicate = [](BoxId a, BoxId b) { return a < b && (a + b) % 3 != 0; };
            world.set_pair_predicate(predicate);
        }
        for (auto& [id, e] : entries) {
            if (scenario.filters && chance(random, 0.5)) {
                e.filter = new_filter(random, scenario);
                world.set_filter(id, e.filter);
            }
            if (chance(random, scenario.static_share)) {
                e.is_static = true;
                world.set_static(id, true);
            }
        }
        for (int step = 0; step < scenario.steps; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            if (step > 0) advance(random, scenario, world, entries, next);
            std::vector<Pair> pairs;
            const DetectStats stats = world.detect(pairs);
            EXPECT_EQ(stats.pairs, pairs.size());
            EXPECT_EQ(stats.boxes, entries.size());
            EXPECT_TRUE(same_pairs(pairs, expected_pairs(entries, predicate)));
            if (::testing::Test::HasFailure()) return;
        }
        for (const auto& [id, e] : entries) {
            ASSERT_EQ(world.filter(id), e.filter);
            ASSERT_EQ(world.is_static(id), e.is_static);
        }
    }

    void advance(Random& random, const Scenario& scenario, World<Real, Dim>& world,
                 std::map<BoxId, Entry<Real, Dim>>& entries, BoxId& next) {
        std::vector<BoxId> ids;
        for (const auto& [id, e] : entries) ids.push_back(id);
        std::vector<BoxId> moved;
        std::vector<BoxT> boxes;
        for (const BoxId id : ids) {
            auto& e = entries[id];
            // Statics move rarely (each such move is a rebuild), the others every step.
            if (e.is_static && !chance(random, 0.01)) continue;
            e.box = chance(random, 0.003) ? random_box<Real, Dim>(random, 0, space_, 1.0, 2.0)
                                          : perturbed(random, e.box, 1e-3 * space_, 1e-2);
            moved.push_back(id);
            boxes.push_back(e.box);
        }
        world.update(moved, boxes);
        for (const BoxId id : ids) {
            if (!chance(random, 0.02)) continue;
            world.remove(id);
            entries.erase(id);
        }
        const std::size_t arrivals = uniform_index(random, 10);
        for (std::size_t i = 0; i < arrivals; ++i) {
            const BoxId id = next++;
            const BoxT box = random_box<Real, Dim>(random, 0, space_, 1.0, 2.0);
            world.insert(id, box);
            entries[id] = {box, Filter{}, false};
            if (chance(random, scenario.static_share)) {
                world.set_static(id, true);
                entries[id].is_static = true;
            }
        }
        for (auto& [id, e] : entries) {
            if (scenario.filters && chance(random, 0.02)) {
                e.filter = new_filter(random, scenario);
                world.set_filter(id, e.filter);
            }
            if (scenario.static_share > 0 && chance(random, 0.005)) {
                e.is_static = !e.is_static;
                world.set_static(id, e.is_static);
            }
        }
    }

    [[nodiscard]] static Filter new_filter(Random& random, const Scenario& scenario) {
        switch (scenario.values) {
            case FilterValues::layered:
                return layered_filter(random);
            case FilterValues::many:
                return many_valued_filter(random);
            case FilterValues::random:
                break;
        }
        return random_filter(random);
    }

    double space_ = 0;
};

TYPED_TEST_SUITE(WorldFiltersTest, WorldTypes, WorldTypeNames);

TYPED_TEST(WorldFiltersTest, RandomFilterBitsMatchBruteForce) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) this->run({}, seed);
}

TYPED_TEST(WorldFiltersTest, RandomFilterBitsWithLargeIdsAndCategoriesMatchBruteForce) {
    Scenario scenario;
    scenario.first_id = BoxId{1} << 40;
    this->run(scenario, 4);
}

TYPED_TEST(WorldFiltersTest, LayersAndSetsDetectedClassByClassMatchBruteForce) {
    Scenario scenario;
    scenario.values = FilterValues::layered;
    for (std::uint64_t seed = 41; seed <= 42; ++seed) this->run(scenario, seed);
    scenario.static_share = 0.3;
    this->run(scenario, 43);
    scenario.first_id = BoxId{1} << 40;
    this->run(scenario, 44);
}

TYPED_TEST(WorldFiltersTest, MoreFilterValuesThanTheClassesKeepMatchBruteForce) {
    Scenario scenario;
    scenario.values = FilterValues::many;
    scenario.static_share = 0.2;
    this->run(scenario, 51);
}

TYPED_TEST(WorldFiltersTest, StaticsThatMoveLeaveAndTurnDynamicMatchBruteForce) {
    Scenario scenario;
    scenario.filters = false;
    scenario.static_share = 0.6;
    for (std::uint64_t seed = 11; seed <= 13; ++seed) this->run(scenario, seed);
}

TYPED_TEST(WorldFiltersTest, StaticsWithFiltersMatchBruteForce) {
    Scenario scenario;
    scenario.static_share = 0.5;
    for (std::uint64_t seed = 21; seed <= 23; ++seed) this->run(scenario, seed);
}

TYPED_TEST(WorldFiltersTest, PredicateWithFiltersAndStaticsMatchesBruteForce) {
    Scenario scenario;
    scenario.static_share = 0.3;
    scenario.predicate = true;
    this->run(scenario, 31);
}

TYPED_TEST(WorldFiltersTest, WithASkinFiltersClassesStaticsAndPredicateMatchBruteForce) {
    // A skin a few steps of motion wide, and one far thinner than a step (it steps aside).
    for (const double skin : {0.1, 1e-4}) {
        SCOPED_TRACE(::testing::Message() << "skin " << skin);
        Scenario scenario;
        scenario.skin = skin;
        scenario.static_share = 0.2;
        this->run(scenario, 61);
        scenario.values = FilterValues::layered;
        this->run(scenario, 62);
        scenario.predicate = true;
        scenario.first_id = BoxId{1} << 40;
        this->run(scenario, 63);
    }
}

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
