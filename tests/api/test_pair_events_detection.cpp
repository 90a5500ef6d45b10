// SPDX-License-Identifier: MIT
// Pair events through World::detect and Detector::detect against brute force, over many steps
// of random changes. Each body carries a number of its own (a new one for every insertion), so
// that the expected events are those of bodies, whatever names they go by: a pair of bodies
// begins when it overlaps now and did not before, and ends the other way round; begun pairs
// are named as now, ended ones as before.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/detector.hpp"
#include "smb/pair_events.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// Under the sanitizers the scenes hold a quarter of the boxes in the same space: fewer boxes,
/// each with fewer contacts, so about the square as few events.
constexpr std::size_t kEventReduction = kScaleDivisor * kScaleDivisor;

using BodyPair = std::pair<std::uint64_t, std::uint64_t>;
/// The pairs of one step: each pair of bodies, and the names it went by.
using NamedPairs = std::map<BodyPair, Pair>;

NamedPairs name_pairs(const std::vector<Pair>& pairs, const std::map<BoxId, std::uint64_t>& body_of) {
    NamedPairs named;
    for (const Pair& pair : pairs) {
        const std::uint64_t x = body_of.at(pair.a);
        const std::uint64_t y = body_of.at(pair.b);
        named.emplace(BodyPair{std::min(x, y), std::max(x, y)}, pair);
    }
    return named;
}

/// The pairs of `from` whose bodies are not a pair of `without`, by their names in `from`.
std::vector<Pair> missing(const NamedPairs& from, const NamedPairs& without) {
    std::vector<Pair> out;
    for (const auto& [bodies, names] : from) {
        if (!without.contains(bodies)) out.push_back(names);
    }
    std::sort(out.begin(), out.end());
    return out;
}

/// Events seen over a test, to check that it exercised them.
struct EventCounts {
    std::size_t begun = 0;
    std::size_t ended = 0;
};

void expect_events(const PairEvents& events, const NamedPairs& before, const NamedPairs& now, int step,
                   EventCounts& counts) {
    counts.begun += events.begun().size();
    counts.ended += events.ended().size();
    EXPECT_EQ(std::vector<Pair>(events.begun().begin(), events.begun().end()), missing(now, before)) << step;
    EXPECT_EQ(std::vector<Pair>(events.ended().begin(), events.ended().end()), missing(before, now)) << step;
}

template <typename WorldType>
class WorldPairEventsTest : public ::testing::Test {};
TYPED_TEST_SUITE(WorldPairEventsTest, WorldTypes, WorldTypeNames);

/// Many steps of removals, reinsertions, teleports and a clear(). With `statics`, one box in
/// ten is static (the world then detects on its filtered path), and pairs of two statics are
/// neither reported nor events.
template <typename WorldType>
void world_events_against_brute_force(bool statics, double skin = 0) {
    using Real = typename WorldType::real_type;
    constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;
    Random random(statics ? 7002 : 7001);
    WorldSettings settings = test_settings();
    settings.skin = skin;
    WorldType world(settings);
    PairEvents events;
    std::map<BoxId, BoxT> boxes;
    std::map<BoxId, std::uint64_t> body_of;
    std::uint64_t next_body = 0;
    const double side = Dim == 2 ? 40 : 14;
    auto insert = [&](BoxId id) {
        const BoxT box = random_box<Real, Dim>(random, 0, side, 0.5, 2);
        world.insert(id, box);
        if (statics && id % 10 == 0) world.set_static(id, true);
        boxes[id] = box;
        body_of[id] = next_body++;
    };
    for (BoxId id = 0; id < scaled(300); ++id) insert(id * 3);
    NamedPairs before;
    std::vector<Pair> pairs;
    EventCounts counts;
    for (int step = 0; step < 40; ++step) {
        if (step > 0) {
            std::vector<BoxId> ids;
            for (const auto& [id, box] : boxes) ids.push_back(id);
            for (const BoxId id : ids) {
                const double roll = uniform(random, 0, 1);
                if (roll < 0.03) {  // removed for good
                    world.remove(id);
                    boxes.erase(id);
                    body_of.erase(id);
                } else if (roll < 0.06) {  // removed and inserted again: a new body
                    world.remove(id);
                    insert(id);
                } else if (roll < 0.08) {  // teleported: the same body
                    const BoxT box = random_box<Real, Dim>(random, 0, side, 0.5, 2);
                    world.update(id, box);
                    boxes[id] = box;
                } else {
                    const BoxT box = perturbed<Real, Dim>(random, boxes[id], 0.3, 0.05);
                    world.update(id, box);
                    boxes[id] = box;
                }
            }
            for (int k = 0; k < 6; ++k) {
                const BoxId id = 1000 + static_cast<BoxId>(step) * 10 + static_cast<BoxId>(k);
                insert(id);
            }
            if (step == 25) {  // everything goes; some ids come back as new bodies
                world.clear();
                boxes.clear();
                body_of.clear();
                for (BoxId id = 0; id < scaled(200); ++id) insert(id * 3);
            }
        }
        world.detect(pairs, events);
        std::vector<BoxId> ids;
        std::vector<BoxT> list;
        for (const auto& [id, box] : boxes) {
            ids.push_back(id);
            list.push_back(box);
        }
        auto expected = brute_force_pairs<Real, Dim>(ids, list);
        if (statics) std::erase_if(expected, [](const Pair& pair) { return pair.a % 10 == 0 && pair.b % 10 == 0; });
        std::vector<Pair> sorted = pairs;
        sort_pairs(sorted);
        ASSERT_EQ(sorted, expected) << step;
        const NamedPairs now = name_pairs(expected, body_of);
        expect_events(events, before, now, step, counts);
        EXPECT_EQ(events.size(), expected.size());
        before = now;
    }
    EXPECT_GT(counts.begun, 1000U / kEventReduction);
    EXPECT_GT(counts.ended, 500U / kEventReduction);
}

TYPED_TEST(WorldPairEventsTest, ManyStepsAgainstBruteForce) { world_events_against_brute_force<TypeParam>(false); }

TYPED_TEST(WorldPairEventsTest, ManyStepsWithStaticBoxes) { world_events_against_brute_force<TypeParam>(true); }

TYPED_TEST(WorldPairEventsTest, ManyStepsWithASkin) {
    world_events_against_brute_force<TypeParam>(false, 0.5);
    world_events_against_brute_force<TypeParam>(true, 0.5);
}

TEST(WorldPairEvents, RemovedAndReinsertedInPlaceEndsAndBegins) {
    World2d world;
    PairEvents events;
    std::vector<Pair> pairs;
    world.insert(1, Box2d{{0, 0}, {1, 1}});
    world.insert(2, Box2d{{1, 0}, {2, 1}});
    world.detect(pairs, events);
    world.remove(2);
    world.insert(2, Box2d{{1, 0}, {2, 1}});
    world.detect(pairs, events);
    EXPECT_EQ(std::vector<Pair>(events.begun().begin(), events.begun().end()), (std::vector<Pair>{{1, 2}}));
    EXPECT_EQ(std::vector<Pair>(events.ended().begin(), events.ended().end()), (std::vector<Pair>{{1, 2}}));
    // A detection that throws leaves the pairs and the events as they were.
    WorldSettings tight;
    tight.max_pairs_held = 0;
    World2d limited(tight);
    limited.insert(1, Box2d{{0, 0}, {1, 1}});
    limited.insert(2, Box2d{{1, 0}, {2, 1}});
    EXPECT_THROW(limited.detect(pairs, events), PairLimitError);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 2}}));
    EXPECT_EQ(events.begun().size(), 1U);
    EXPECT_EQ(events.size(), 1U);
}

template <typename Real, int Dim>
void detector_swap_removes(std::uint64_t seed) {
    using BoxT = Box<Real, Dim>;
    Random random(seed);
    Detector<Real, Dim> detector;
    PairEvents events;
    std::vector<BoxT> boxes;
    std::vector<std::uint64_t> bodies;  // the body at each index
    std::uint64_t next_body = 0;
    const double side = Dim == 2 ? 40 : 14;
    auto append = [&] {
        boxes.push_back(random_box<Real, Dim>(random, 0, side, 0.5, 2));
        bodies.push_back(next_body++);
    };
    for (std::size_t i = 0; i < scaled(300); ++i) append();
    NamedPairs before;
    std::vector<Pair> pairs;
    EventCounts counts;
    for (int step = 0; step < 40; ++step) {
        if (step > 0) {
            for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = perturbed<Real, Dim>(random, boxes[i], 0.3, 0.05);
            const std::size_t removals = uniform_index(random, 12);
            for (std::size_t k = 0; k < removals && !boxes.empty(); ++k) {
                const std::size_t removed = uniform_index(random, boxes.size());
                const std::size_t last = boxes.size() - 1;
                boxes[removed] = boxes[last];
                bodies[removed] = bodies[last];
                boxes.pop_back();
                bodies.pop_back();
                events.swap_remove(removed, last);
                if (k % 3 == 0) append();  // appended between swap-removes
            }
            for (int k = 0; k < 3 && !boxes.empty(); ++k) {  // a new body at an old index
                const std::size_t index = uniform_index(random, boxes.size());
                boxes[index] = random_box<Real, Dim>(random, 0, side, 0.5, 2);
                bodies[index] = next_body++;
                events.replace(index);
            }
            if (!boxes.empty()) {  // a teleport: the same body
                boxes[uniform_index(random, boxes.size())] = random_box<Real, Dim>(random, 0, side, 0.5, 2);
            }
            for (int k = 0; k < 4; ++k) append();
        }
        detector.detect(boxes, pairs, events);
        const auto expected = brute_force_pairs<Real, Dim>(std::span<const BoxT>(boxes));
        std::vector<Pair> sorted = pairs;
        sort_pairs(sorted);
        ASSERT_EQ(sorted, expected) << step;
        std::map<BoxId, std::uint64_t> body_of;
        for (std::size_t i = 0; i < bodies.size(); ++i) body_of[i] = bodies[i];
        const NamedPairs now = name_pairs(expected, body_of);
        expect_events(events, before, now, step, counts);
        before = now;
    }
    EXPECT_GT(counts.begun, 1000U / kEventReduction);
    EXPECT_GT(counts.ended, 500U / kEventReduction);
}

TEST(DetectorPairEvents, SwapRemovesAgainstBruteForce2f) { detector_swap_removes<float, 2>(7101); }
TEST(DetectorPairEvents, SwapRemovesAgainstBruteForce2d) { detector_swap_removes<double, 2>(7102); }
TEST(DetectorPairEvents, SwapRemovesAgainstBruteForce3f) { detector_swap_removes<float, 3>(7103); }
TEST(DetectorPairEvents, SwapRemovesAgainstBruteForce3d) { detector_swap_removes<double, 3>(7104); }

TEST(DetectorPairEvents, InvalidBoxChangesNothing) {
    Detector3d detector;
    PairEvents events;
    std::vector<Box3d> boxes{{{0, 0, 0}, {1, 1, 1}}, {{1, 0, 0}, {2, 1, 1}}};
    std::vector<Pair> pairs;
    detector.detect(boxes, pairs, events);
    boxes.push_back({{2, 0, 0}, {1, 1, 1}});
    EXPECT_THROW(detector.detect(boxes, pairs, events), InvalidBoxError);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 1}}));
    EXPECT_EQ(events.begun().size(), 1U);
    boxes.pop_back();
    detector.detect(boxes, pairs, events);
    EXPECT_TRUE(events.begun().empty());
    EXPECT_TRUE(events.ended().empty());
}

}  // namespace
}  // namespace smb::test
