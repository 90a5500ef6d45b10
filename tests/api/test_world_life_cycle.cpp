// SPDX-License-Identifier: MIT
// A World through its life: mass jumps, reinsertion, clearing and refilling, repeated detections,
// ids near the top of their range, crowds on several threads, sinks, moves. Every world is
// checked against brute force after each detection (the fixture of test_world_edge_cases.cpp).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/world_edge_fixture.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// `count` unit boxes on an integer lattice of `side` places per axis, two units apart, so that
/// no two overlap; the lattice spans [0, 2 side - 1] on every axis.
template <class R, int D>
std::vector<Box<R, D>> boxes_apart(std::size_t count, std::size_t side) {
    std::vector<Box<R, D>> boxes;
    for (std::size_t i = 0; i < count; ++i) {
        Box<R, D> box;
        std::size_t rest = i;
        for (int k = 0; k < D; ++k) {
            box.min[k] = static_cast<R>(2 * (rest % side));
            box.max[k] = box.min[k] + R{1};
            rest /= side;
        }
        boxes.push_back(box);
    }
    return boxes;
}

/// The pairs `world` (set to several threads) reports for `boxes`, checked equal, in order, to
/// those of a world on one thread.
template <class R, int D>
std::vector<Pair> pairs_beside_one_thread(World<R, D>& world, const std::vector<Box<R, D>>& boxes) {
    World<R, D> alone(test_settings());
    world.assign(boxes);
    alone.assign(boxes);
    std::vector<Pair> threaded, single;
    world.detect(threaded);
    alone.detect(single);
    EXPECT_EQ(threaded, single) << "the thread count changed the pairs or their order";
    return threaded;
}

template <typename WorldType>
class WorldLifeCycleTest : public WorldEdgeCaseTest<WorldType> {};

TYPED_TEST_SUITE(WorldLifeCycleTest, WorldTypes, WorldTypeNames);

TYPED_TEST(WorldLifeCycleTest, MostBoxesJumpFarAway) {
    Random random(1801);
    const std::size_t count = scaled(1000);
    std::vector<typename TestFixture::BoxT> boxes;
    for (std::size_t i = 0; i < count; ++i)
        boxes.push_back(random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 30, 0.5, 2));
    this->assign(boxes);
    this->check("before the jump");
    auto jumped = boxes;
    for (std::size_t i = 0; i < count; ++i) {
        if (i % 10 == 0) continue;
        jumped[i] = random_box<typename TestFixture::Real, TestFixture::Dim>(random, 5000, 5030, 0.5, 2);
    }
    this->assign(jumped);
    this->check("90% jumped away");
    this->assign(boxes);
    this->check("and back");
}

TYPED_TEST(WorldLifeCycleTest, RemoveThenReinsertSameIdBetweenDetections) {
    Random random(1901);
    for (BoxId id = 0; id < 200; ++id)
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
    this->check("start");
    for (BoxId id = 0; id < 200; id += 3) {
        const auto box = this->reference_.box(id);
        this->remove(id);
        this->insert(id, box);
    }
    this->check("reinserted in place");
    for (BoxId id = 1; id < 200; id += 3) {
        this->remove(id);
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
        this->update(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
    }
    this->check("reinserted elsewhere and updated");
    // Insert, then remove before any detection saw it.
    this->insert(5000, this->cube(0, 20));
    this->remove(5000);
    this->check("inserted and removed unseen");
}

TYPED_TEST(WorldLifeCycleTest, RemoveEverythingThenInsertAgain) {
    Random random(2001);
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    for (BoxId id = 0; id < 300; ++id) {
        ids.push_back(id * 5);
        boxes.push_back(random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
    }
    this->insert_all(ids, boxes);
    this->check("full");
    this->world_.remove(ids);
    for (const BoxId id : ids) this->reference_.remove(id);
    EXPECT_TRUE(this->check("emptied by a batch remove").empty());
    this->insert_all(ids, boxes);
    this->check("same ids back");
    for (const BoxId id : ids) this->remove(id);
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] += 1;
    this->insert_all(ids, boxes);
    this->check("emptied one by one, refilled under new ids");
}

TYPED_TEST(WorldLifeCycleTest, ClearAndReuse) {
    Random random(2101);
    for (BoxId id = 0; id < 200; ++id)
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
    this->check("first life");
    this->world_.clear();
    this->reference_.clear();
    EXPECT_EQ(this->world_.size(), 0u);
    EXPECT_FALSE(this->world_.contains(0));
    EXPECT_TRUE(this->check("cleared").empty());
    for (BoxId id = 100; id < 400; ++id)
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 20, 0.5, 2));
    this->check("second life");
    // clear() with changes still pending, then straight on.
    this->shift_all(0.5);
    this->world_.clear();
    this->reference_.clear();
    this->insert(1, this->cube(0, 1));
    this->insert(2, this->cube(1, 2));
    EXPECT_EQ(this->check("third life").size(), 1u);
}

TYPED_TEST(WorldLifeCycleTest, RepeatedDetectionWithoutChanges) {
    Random random(2201);
    for (BoxId id = 0; id < scaled(500); ++id)
        this->insert(id * 3 + 1, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 25, 0.5, 2));
    const auto first = this->check("first");
    // The first detection reads the boxes in the order they came; every later one in the order
    // the cells left, so the list is the same from the second detection on, order included.
    std::vector<Pair> second;
    this->world_.detect(second);
    std::vector<Pair> expected = first;
    sort_pairs(expected);
    EXPECT_TRUE(same_pairs(second, expected));
    for (int i = 0; i < 5; ++i) {
        std::vector<Pair> again;
        this->world_.detect(again);
        EXPECT_EQ(again, second) << "detection " << i + 3 << " without changes differs";
    }
}

TYPED_TEST(WorldLifeCycleTest, IdsNearTheTopOfTheRange) {
    constexpr BoxId top = std::numeric_limits<BoxId>::max();
    this->insert(top, this->cube(0, 2));
    this->insert(top - 1, this->cube(1, 3));
    this->insert(0, this->cube(2, 4));
    this->insert(top / 2, this->cube(10, 11));
    this->check("huge ids");
    this->remove(top);
    this->update(top / 2, this->cube(0, 1));
    this->check("huge ids after changes");
}

TYPED_TEST(WorldLifeCycleTest, CrowdOfIdenticalBoxesOnSeveralThreadsHoldsNoPairList) {
    // 3 000 identical boxes: 4.5 million pairs (72 MB) in one cell, more than a column may
    // buffer while the threads share the cells, so the column is checked again straight into
    // the sink.
    WorldSettings settings = test_settings();
    settings.threads = 2;
    World<typename TestFixture::Real, TestFixture::Dim> world(settings);
    World<typename TestFixture::Real, TestFixture::Dim> alone(test_settings());
    const std::size_t n = 3000;
    for (BoxId id = 0; id < n; ++id) {
        world.insert(id, this->cube(0, 1));
        alone.insert(id, this->cube(0, 1));
    }
    std::size_t count = 0;
    std::size_t largest_chunk = 0;
    std::vector<Pair> streamed;
    world.detect([&](std::span<const Pair> chunk) {
        count += chunk.size();
        largest_chunk = std::max(largest_chunk, chunk.size());
        streamed.insert(streamed.end(), chunk.begin(), chunk.end());
    });
    EXPECT_EQ(count, n * (n - 1) / 2);
    EXPECT_LE(largest_chunk, settings.pair_chunk_size);
    // The world keeps no copy of the pairs: at most one capped column buffer (4 MiB) and its
    // growth, far less than the pairs themselves.
    EXPECT_LT(world.bytes_held(), std::size_t{16} << 20);
    EXPECT_LT(world.bytes_held(), count * sizeof(Pair) / 4);
    std::vector<Pair> one_thread;
    alone.detect(one_thread);
    EXPECT_EQ(streamed, one_thread) << "the thread count changed the order";
}

TYPED_TEST(WorldLifeCycleTest, HugeBoxOverMoreBoxesThanABufferHoldsOnSeveralThreads) {
    // One box over 270 000 small ones: its pairs outgrow the 2^18 an oversized box may buffer
    // while the threads share the oversized boxes, so it is checked again into the sink.
    using R = typename TestFixture::Real;
    constexpr int D = TestFixture::Dim;
    const std::size_t n = 270000;
    const std::size_t side = D == 2 ? 520 : 65;  // side^Dim >= n grid places
    std::vector<typename TestFixture::BoxT> boxes = boxes_apart<R, D>(n, side);
    typename TestFixture::BoxT huge;
    for (int k = 0; k < D; ++k) {
        huge.min[k] = -1;
        huge.max[k] = static_cast<R>(2 * side + 1);
    }
    boxes.push_back(huge);
    WorldSettings settings = test_settings();
    settings.threads = 2;
    World<R, D> world(settings);
    const std::vector<Pair> threaded = pairs_beside_one_thread(world, boxes);
    EXPECT_EQ(threaded.size(), n);                       // the small boxes are apart: every pair has the huge box
    if (test_pipeline() == Pipeline::persistent_cuts) {  // no copy of the pairs is kept
        EXPECT_LT(world.bytes_held(), n * (sizeof(typename TestFixture::BoxT) + 256));
    }
}

TYPED_TEST(WorldLifeCycleTest, OversizedBoxesOverlappingOneAnotherBeyondABufferOnSeveralThreads) {
    // 760 boxes over the whole scene, each overlapping every other: their 288 420 pairs among
    // themselves outgrow what the threads buffer for the oversized boxes' sweep, which is then
    // run again into the sink; each also overlaps every one of the small boxes, which lie apart.
    using R = typename TestFixture::Real;
    constexpr int D = TestFixture::Dim;
    const std::size_t small = 4000;  // most boxes, so that the planes are kept a small box apart
    const std::size_t big = 760;
    const std::size_t side = D == 2 ? 64 : 16;  // side^Dim >= small grid places
    std::vector<typename TestFixture::BoxT> boxes = boxes_apart<R, D>(small, side);
    for (std::size_t i = 0; i < big; ++i) {
        typename TestFixture::BoxT box;
        for (int k = 0; k < D; ++k) {
            box.min[k] = static_cast<R>(-1.0 - static_cast<double>(i % 37) / 8);
            box.max[k] = static_cast<R>(2.0 * static_cast<double>(side) + static_cast<double>(i % 11) / 4);
        }
        boxes.push_back(box);
    }
    WorldSettings settings = test_settings();
    settings.threads = 2;
    settings.profile = true;
    World<R, D> world(settings);
    const std::vector<Pair> threaded = pairs_beside_one_thread(world, boxes);
    if (test_pipeline() == Pipeline::persistent_cuts) {
        EXPECT_EQ(world.last_profile().oversized_boxes, big);
    }
    EXPECT_EQ(threaded.size(), big * (big - 1) / 2 + big * small);
    this->assign(boxes);
    this->check("every big box over every box");
}

TYPED_TEST(WorldLifeCycleTest, PairSinkReceivesEveryPairInBoundedChunks) {
    WorldSettings settings = test_settings();
    settings.pair_chunk_size = 7;
    World<typename TestFixture::Real, TestFixture::Dim> world(settings);
    Random random(2301);
    std::vector<typename TestFixture::BoxT> boxes;
    for (int i = 0; i < 300; ++i)
        boxes.push_back(random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 15, 0.5, 2));
    world.assign(boxes);
    std::vector<Pair> first;  // in the boxes' own order; the two below, in the cells' (see above)
    world.detect(first);
    std::vector<Pair> collected;
    const DetectStats stats = world.detect([&collected](std::span<const Pair> chunk) {
        EXPECT_FALSE(chunk.empty());
        EXPECT_LE(chunk.size(), 7u);
        collected.insert(collected.end(), chunk.begin(), chunk.end());
    });
    EXPECT_EQ(stats.pairs, collected.size());
    EXPECT_TRUE(same_pairs(collected, brute_force_pairs<typename TestFixture::Real, TestFixture::Dim>(
                                          std::span<const typename TestFixture::BoxT>(boxes))));
    std::vector<Pair> listed;
    world.detect(listed);
    EXPECT_EQ(listed, collected) << "detect(vector) and detect(sink) report differently";
}

TYPED_TEST(WorldLifeCycleTest, UnderASkinABoxMovedIntoARemovedBoxsPlaceIsReportedUnderItsOwnId) {
    if (test_pipeline() == Pipeline::paper_lists) GTEST_SKIP() << "the paper's lists keep no skin";
    // Removing a box moves the box of the last slot into its slot. Put exactly where the removed
    // one was, the moved box lies inside the fat box the skin kept for that slot, so the slot's
    // candidates stand and only its name changes. `slots` follows the store's compaction.
    WorldSettings settings = test_settings();
    settings.skin = 1.0;
    this->world_ = World<typename TestFixture::Real, TestFixture::Dim>(settings);
    Random random(2301);
    std::vector<BoxId> slots;
    for (BoxId id = 0; id < 120; ++id) {
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 12, 0.5, 2));
        slots.push_back(id);
    }
    this->check("start");
    for (int step = 0; step < 20; ++step) {
        const std::size_t hole = uniform_index(random, slots.size() - 1);
        const auto box = this->reference_.box(slots[hole]);
        this->remove(slots[hole]);
        this->update(slots.back(), box);
        slots[hole] = slots.back();
        slots.pop_back();
        this->check("a box put in the place of a removed one");
        EXPECT_GT(this->world_.last_stats().skin_candidates, 0u);
    }
}

TYPED_TEST(WorldLifeCycleTest, IdsFollowTheirBoxesThroughRemovalsWhileIdsPast32BitsComeAndGo) {
    // Where every id fits 32 bits, a detection carries the ids into the next order instead of
    // reading them from the store again; removals move boxes to other slots, and an id past
    // 32 bits stops the carrying until it leaves. Every step moves, removes and inserts.
    Random random(2401);
    auto fresh_box = [&random] {
        return random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 25, 0.5, 2);
    };
    std::vector<BoxId> present;
    BoxId next_id = 0;
    for (; next_id < 600; ++next_id) {
        this->insert(next_id, fresh_box());
        present.push_back(next_id);
    }
    this->check("start");
    const BoxId wide = (BoxId{1} << 32) + 5;
    for (int step = 0; step < 30; ++step) {
        for (const BoxId id : present) {
            if (uniform(random, 0, 1) < 0.5) this->update(id, fresh_box());
        }
        for (int k = 0; k < 20; ++k) {
            const std::size_t at = uniform_index(random, present.size() - 1);
            this->remove(present[at]);
            present[at] = present.back();
            present.pop_back();
        }
        for (int k = 0; k < 20; ++k) {
            this->insert(next_id, fresh_box());
            present.push_back(next_id++);
        }
        if (step == 10) this->insert(wide, fresh_box());
        if (step == 20) this->remove(wide);
        this->check("moves, removals and insertions");
    }
}

TYPED_TEST(WorldLifeCycleTest, MovedWorldKeepsItsBoxes) {
    Random random(2401);
    for (BoxId id = 0; id < 100; ++id)
        this->insert(id, random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 10, 0.5, 2));
    this->check("before the move");
    World<typename TestFixture::Real, TestFixture::Dim> moved(std::move(this->world_));
    this->world_ = std::move(moved);
    this->shift_all(0.3);
    this->check("after moving the world twice");
}

}  // namespace
}  // namespace smb::test
