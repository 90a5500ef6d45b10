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
        World<Real, Dim> world(test_settings());
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

TEST(WorldFilters, StaticsTouchingWithinAFloatOfAMovingBoxPairExactly) {
    // The moving boxes test their cached statics as floats rounded outward and go to the exact
    // boxes only where the float test cannot tell: faces that meet, or miss by a double's ulp,
    // at coordinates no float holds, on every axis and both sides.
    World3d world;
    BoxId id = 0;
    std::vector<Pair> expected;
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 40; ++i) {
            const double x = 0.1 + 0.37 * i + 1e-9 * k;  // not a float
            for (const int side : {-1, 1}) {
                for (const int steps : {-2, -1, 0, 1, 2}) {
                    double face = x;  // the moving box's face, `steps` ulps from the static's
                    for (int s = 0; s < std::abs(steps); ++s) face = std::nextafter(face, steps > 0 ? 1e9 : -1e9);
                    Box3d fixed{{0, 0, 0}, {1, 1, 1}};
                    Box3d moving{{0, 0, 0}, {1, 1, 1}};
                    const double offset = 20.0 * static_cast<double>(id + 1);  // apart from the others on another axis
                    const int other = (k + 1) % 3;
                    fixed.min[other] = moving.min[other] = offset;
                    fixed.max[other] = moving.max[other] = offset + 1;
                    // side 1: the static below x, the moving box from `face` up; side -1 mirrored.
                    const bool meet = side > 0 ? steps <= 0 : steps >= 0;
                    if (side > 0) {
                        fixed.min[k] = x - 1;
                        fixed.max[k] = x;
                        moving.min[k] = face;
                        moving.max[k] = face + 1;
                    } else {
                        fixed.min[k] = x;
                        fixed.max[k] = x + 1;
                        moving.min[k] = face - 1;
                        moving.max[k] = face;
                    }
                    world.insert(id, fixed);
                    world.set_static(id, true);
                    world.insert(id + 1, moving);
                    if (meet) expected.push_back({id, id + 1});
                    id += 2;
                }
            }
        }
    }
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, expected);
}

/// Statics whose faces lie within a few steps of a moving box's lattice (a 32767th of its fat
/// box's side, quantized_bounds.hpp) of the moving boxes' faces, on every axis and both sides,
/// and moving boxes that creep across them by a fraction of a step at each detection, inside
/// their fat boxes: every detection against brute force.
/// Brute force over statics (every id below every moving id) and moving boxes: the pairs of a
/// static and a moving box and of two moving boxes, sorted.
template <std::floating_point Real, int Dim>
std::vector<Pair> static_and_moving_pairs(const std::map<BoxId, Box<Real, Dim>>& statics,
                                          const std::map<BoxId, Box<Real, Dim>>& moving) {
    std::vector<Pair> expected;
    for (const auto& [sid, s] : statics) {
        for (const auto& [mid, b] : moving) {
            if (overlaps(s, b)) expected.push_back({sid, mid});
        }
    }
    for (auto a = moving.begin(); a != moving.end(); ++a) {
        for (auto b = std::next(a); b != moving.end(); ++b) {
            if (overlaps(a->second, b->second)) expected.push_back({a->first, b->first});
        }
    }
    std::sort(expected.begin(), expected.end());
    return expected;
}

template <std::floating_point Real, int Dim>
void check_statics_within_a_lattice_step() {
    using B = Box<Real, Dim>;
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    const Real step = static_cast<Real>(2.0 / 32767);  // the lattice step of a fat box of side 2
    BoxId id = 0;
    for (int k = 0; k < Dim; ++k) {
        for (const int side : {-1, 1}) {
            for (const double steps : {-3.0, -1.0, -0.5, 0.0, 0.5, 1.0, 3.0}) {
                for (const int ulps : {-1, 0, 1}) {
                    B s;
                    for (int j = 0; j < Dim; ++j) {
                        s.min[j] = 0;
                        s.max[j] = 1;
                    }
                    Real face = static_cast<Real>(side < 0 ? 0.0 : 1.0) + static_cast<Real>(steps) * step;
                    for (int u = 0; u < std::abs(ulps); ++u) face = std::nextafter(face, static_cast<Real>(10 * ulps));
                    // side -1: the static ends at `face` near the moving boxes' low faces; +1 mirrored.
                    s.min[k] = side < 0 ? face - 1 : face;
                    s.max[k] = side < 0 ? face : face + 1;
                    statics[id] = s;
                    world.insert(id, s);
                    world.set_static(id, true);
                    ++id;
                }
            }
        }
    }
    for (int m = 0; m < 3; ++m) {
        B b;
        for (int j = 0; j < Dim; ++j) {
            b.min[j] = 0;
            b.max[j] = 1;
        }
        moving[1000 + m] = b;
        world.insert(1000 + m, b);
    }
    std::vector<Pair> pairs;
    for (int t = 0; t < 40; ++t) {
        // Each moving box creeps by its own fraction of a step along its own direction.
        for (auto& [mid, b] : moving) {
            const auto m = static_cast<int>(mid - 1000);
            for (int j = 0; j < Dim; ++j) {
                const Real by =
                    static_cast<Real>((j + m) % 2 == 0 ? 1 : -1) * step * static_cast<Real>(0.13 + 0.11 * m);
                b.min[j] = static_cast<Real>(-3) * step + by * static_cast<Real>(t) + (m == 2 ? step : Real(0));
                b.max[j] = 1 + static_cast<Real>(3) * step - by * static_cast<Real>(t) * static_cast<Real>(m);
            }
            world.update(mid, b);
        }
        world.detect(pairs);
        const std::vector<Pair> expected = static_and_moving_pairs(statics, moving);
        ASSERT_TRUE(same_pairs(pairs, expected)) << "detection " << t;
    }
}

TEST(WorldFilters, StaticsWithinALatticeStepOfMovingBoxesPairExactly) {
    check_statics_within_a_lattice_step<double, 3>();
    check_statics_within_a_lattice_step<float, 3>();
    check_statics_within_a_lattice_step<double, 2>();
    check_statics_within_a_lattice_step<float, 2>();
}

/// Statics of every kind the grid tells apart (static_grid.hpp): small ones found by their home
/// cell (points among them), wider ones listed in every cell they cover, and floors kept apart;
/// moving boxes of mixed sizes that wander, jump and stop among them; against brute force.
template <std::floating_point Real, int Dim>
void check_statics_of_mixed_sizes(std::uint64_t seed) {
    using B = Box<Real, Dim>;
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Random random(seed);
    const double space = Dim == 3 ? 30 : 120;
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    std::vector<BoxId> static_ids;
    for (BoxId id = 0; id < 600; ++id) {
        const double kind = uniform(random, 0, 1);
        B b = kind < 0.1    ? random_box<Real, Dim>(random, 0, space, 0, 0)      // points
              : kind < 0.8  ? random_box<Real, Dim>(random, 0, space, 0.5, 1.5)  // small
              : kind < 0.98 ? random_box<Real, Dim>(random, 0, space, 3, 8)      // wider
                            : random_box<Real, Dim>(random, 0, space, 0.5, 1.5);
        if (kind >= 0.98) {  // a floor across the whole space on every axis but one
            for (int k = 1; k < Dim; ++k) {
                b.min[k] = static_cast<Real>(-10);
                b.max[k] = static_cast<Real>(space + 10);
            }
        }
        statics[id] = b;
        world.insert(id, b);
        static_ids.push_back(id);
    }
    world.set_static(static_ids, true);
    for (BoxId id = 1000; id < 1150; ++id) {
        moving[id] = random_box<Real, Dim>(random, 0, space, 0.2, 3);
        world.insert(id, moving[id]);
    }
    std::vector<Pair> pairs;
    for (int step = 0; step < 20; ++step) {
        std::vector<BoxId> ids;
        std::vector<B> boxes;
        for (auto& [id, b] : moving) {
            if (chance(random, 0.2)) continue;  // stays where it is
            b = chance(random, 0.02) ? random_box<Real, Dim>(random, 0, space, 0.2, 3)
                                     : perturbed(random, b, 0.3, 0.05);
            ids.push_back(id);
            boxes.push_back(b);
        }
        world.update(ids, boxes);
        world.detect(pairs);
        const std::vector<Pair> expected = static_and_moving_pairs(statics, moving);
        ASSERT_TRUE(same_pairs(pairs, expected)) << "step " << step;
    }
}

TEST(WorldFilters, StaticsOfMixedSizesMatchBruteForce) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        check_statics_of_mixed_sizes<double, 3>(seed);
        check_statics_of_mixed_sizes<float, 3>(seed);
        check_statics_of_mixed_sizes<double, 2>(seed);
        check_statics_of_mixed_sizes<float, 2>(seed);
    }
}

/// Moving boxes that creep among the statics by steps far below their size (1/1024 on an axis
/// a step, on a binary grid, so that faces land on the statics' faces exactly), now and then
/// turning back: any answer a step reuses after the box moved past a face shows as a pair
/// missed or too many, against brute force at every step.
template <std::floating_point Real, int Dim>
void check_boxes_creeping_across_static_faces(std::uint64_t seed) {
    using B = Box<Real, Dim>;
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Random random(seed);
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    std::vector<BoxId> static_ids;
    const int per_axis = Dim == 3 ? 5 : 10;
    const int cells = Dim == 3 ? per_axis * per_axis * per_axis : per_axis * per_axis;
    for (BoxId id = 0; id < static_cast<BoxId>(cells); ++id) {  // unit boxes 0.5 apart
        B b;
        auto rest = static_cast<int>(id);
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = static_cast<Real>(1.5 * (rest % per_axis));
            b.max[k] = b.min[k] + 1;
            rest /= per_axis;
        }
        statics[id] = b;
        world.insert(id, b);
        static_ids.push_back(id);
    }
    world.set_static(static_ids, true);
    constexpr double kStep = 1.0 / 1024;
    std::map<BoxId, std::array<int, Dim>> pace;  // steps of kStep a detection, on each axis
    for (BoxId id = 1000; id < 1040; ++id) {
        B b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = static_cast<Real>(kStep * static_cast<double>(uniform_index(random, 1536 * per_axis)));
            b.max[k] = b.min[k] + static_cast<Real>(static_cast<double>(1 + uniform_index(random, 64)) / 64);
            pace[id][k] = static_cast<int>(uniform_index(random, 7)) - 3;
        }
        moving[id] = b;
        world.insert(id, b);
    }
    std::vector<Pair> pairs;
    for (int step = 0; step < 300; ++step) {
        std::vector<BoxId> ids;
        std::vector<B> boxes;
        for (auto& [id, b] : moving) {
            for (int k = 0; k < Dim; ++k) {
                if (chance(random, 0.03)) pace[id][k] = -pace[id][k];
                const auto by = static_cast<Real>(kStep * pace[id][k]);
                b.min[k] += by;
                b.max[k] += by;
            }
            ids.push_back(id);
            boxes.push_back(b);
        }
        world.update(ids, boxes);
        world.detect(pairs);
        const std::vector<Pair> expected = static_and_moving_pairs(statics, moving);
        ASSERT_TRUE(same_pairs(pairs, expected)) << "step " << step;
    }
}

TEST(WorldFilters, BoxesCreepingAcrossStaticFacesMatchBruteForce) {
    for (const std::uint64_t seed : {1u, 2u}) {
        check_boxes_creeping_across_static_faces<double, 3>(seed);
        check_boxes_creeping_across_static_faces<float, 3>(seed);
        check_boxes_creeping_across_static_faces<double, 2>(seed);
        check_boxes_creeping_across_static_faces<float, 2>(seed);
    }
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

}  // namespace
}  // namespace smb::test
