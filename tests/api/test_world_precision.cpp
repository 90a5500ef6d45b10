// SPDX-License-Identifier: MIT
// What a World of double boxes holds for its persistent-cut pipeline (floats where they resolve
// the scene, the doubles where they would not), and that the pairs the floats cannot settle are
// settled on the stored doubles: under ids that are not the store's slots, after removals that
// renumber the slots, on one thread and on two.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <random>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/random_boxes.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

struct Scene {
    std::vector<BoxId> ids;
    std::vector<Box3d> boxes;

    std::vector<Pair> expected() const {
        return brute_force_pairs<double, 3>(std::span<const BoxId>(ids), std::span<const Box3d>(boxes));
    }
};

/// Boxes that floats cannot tell apart from touching (near_touching_lattice()), under ids that
/// are neither the slots nor in order.
Scene near_scene() {
    Scene scene;
    std::vector<BoxId>& ids = scene.ids;
    std::vector<Box3d>& boxes = scene.boxes;
    boxes = near_touching_lattice(8);
    ids.resize(boxes.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<BoxId>(7919 * (ids.size() - i) + 13);
    // Inserted in a shuffled order, so that no slot is the index above either.
    std::vector<std::size_t> shuffle(boxes.size());
    std::iota(shuffle.begin(), shuffle.end(), std::size_t{0});
    std::shuffle(shuffle.begin(), shuffle.end(), Random(5));
    std::vector<BoxId> shuffled_ids;
    std::vector<Box3d> shuffled_boxes;
    for (const std::size_t i : shuffle) {
        shuffled_ids.push_back(ids[i]);
        shuffled_boxes.push_back(boxes[i]);
    }
    ids = shuffled_ids;
    boxes = shuffled_boxes;
    return scene;
}

std::vector<Pair> detected(World3d& world) {
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    return pairs;
}

TEST(WorldPrecision, SettlesOnTheStoredDoublesWhatTheFloatsCannot) {
    const Scene scene = near_scene();
    for (const std::size_t threads : {1U, 2U}) {
        SCOPED_TRACE(threads);
        WorldSettings settings;
        settings.threads = threads;
        World3d world(settings);
        EXPECT_EQ(world.last_precision(), HeldPrecision::none);
        world.insert(scene.ids, scene.boxes);
        EXPECT_EQ(detected(world), scene.expected());
        EXPECT_EQ(world.last_precision(), HeldPrecision::floats);
        EXPECT_GT(world.last_retested_pairs(), 0U);
        // Again, warm: the order now follows the cells.
        EXPECT_EQ(detected(world), scene.expected());
        EXPECT_GT(world.last_retested_pairs(), 0U);
    }
}

TEST(WorldPrecision, SettlesOnTheStoredDoublesAfterRemovalsRenumberTheSlots) {
    Scene scene = near_scene();
    World3d world;
    world.insert(scene.ids, scene.boxes);
    EXPECT_EQ(detected(world), scene.expected());
    Random random(11);
    for (int step = 0; step < 6; ++step) {
        SCOPED_TRACE(step);
        // Every fifth box leaves; the survivors' slots are compacted before the next detection.
        std::vector<BoxId> gone;
        Scene kept;
        for (std::size_t i = 0; i < scene.ids.size(); ++i) {
            if (uniform_index(random, 5) == 0)
                gone.push_back(scene.ids[i]);
            else {
                kept.ids.push_back(scene.ids[i]);
                kept.boxes.push_back(scene.boxes[i]);
            }
        }
        world.remove(gone);
        scene = kept;
        EXPECT_EQ(detected(world), scene.expected());
        EXPECT_EQ(world.last_precision(), HeldPrecision::floats);
    }
}

TEST(WorldPrecision, HoldsDoublesWhereFloatsWouldNotResolveTheScene) {
    Random random(3);
    std::vector<Box3d> points;  // boxes of no size: floats would turn them into a crowd
    for (int i = 0; i < 1000; ++i) points.push_back(random_box<double, 3>(random, 0, 100, 0, 0));
    World3d world;
    world.assign(points);
    EXPECT_TRUE(detected(world).empty());
    EXPECT_EQ(world.last_precision(), HeldPrecision::doubles);
    EXPECT_EQ(world.last_retested_pairs(), 0U);

    // Far beyond float range the boxes are held as doubles too, and the pairs stay exact.
    for (Box3d& box : points) {
        for (int k = 0; k < 3; ++k) {
            box.max[k] += 2;
            box.min[k] *= 1e300;
            box.max[k] *= 1e300;
        }
    }
    world.assign(points);
    const std::vector<Pair> expected = brute_force_pairs<double, 3>(std::span<const Box3d>(points));
    EXPECT_EQ(detected(world), expected);
    EXPECT_EQ(world.last_precision(), HeldPrecision::doubles);
}

TEST(WorldPrecision, SaysWhatEachPipelineHeld) {
    const std::vector<Box3d> boxes{Box3d{{0, 0, 0}, {1, 1, 1}}, Box3d{{1, 1, 1}, {2, 2, 2}}};
    World3d world;
    world.assign(boxes);
    EXPECT_EQ(detected(world).size(), 1U);
    EXPECT_EQ(world.last_precision(), HeldPrecision::floats);
    world.clear();
    EXPECT_EQ(world.last_precision(), HeldPrecision::none);
    EXPECT_TRUE(detected(world).empty());
    EXPECT_EQ(world.last_precision(), HeldPrecision::none);

    WorldSettings paper;
    paper.pipeline = Pipeline::paper_lists;
    World3d paper_world(paper);
    paper_world.assign(boxes);
    EXPECT_EQ(detected(paper_world).size(), 1U);
    EXPECT_EQ(paper_world.last_precision(), HeldPrecision::doubles);

    World3f float_world;
    const std::vector<Box3f> float_boxes{Box3f{{0, 0, 0}, {1, 1, 1}}, Box3f{{1, 1, 1}, {2, 2, 2}}};
    float_world.assign(float_boxes);
    std::vector<Pair> pairs;
    float_world.detect(pairs);
    EXPECT_EQ(pairs.size(), 1U);
    EXPECT_EQ(float_world.last_precision(), HeldPrecision::floats);
    EXPECT_EQ(float_world.last_retested_pairs(), 0U);
}

}  // namespace
}  // namespace smb::test
