// SPDX-License-Identifier: MIT
// World filters and static boxes against brute force: random category and mask bits over many
// steps with motion, insertions, removals, teleports and filter changes; static boxes that later
// move, are removed or become dynamic; both together; a predicate; a skin.
// tests/api/test_world_filter_cases.cpp holds small scenes whose pairs are known, and bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <utility>
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

}  // namespace
}  // namespace smb::test
