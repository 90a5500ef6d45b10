// SPDX-License-Identifier: MIT
// The paper's segment rule (WorldSettings::segment_rule = SegmentRule::twice_largest_box) on the
// paper's lists: every segment at least twice the largest box, so no box is ever oversized, and
// the pairs those of brute force while boxes move, jump, arrive and leave. The world tests run
// the whole random and edge-case suites under this rule too (SMB_TEST_PIPELINE=paper-rule).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

WorldSettings paper_settings(SegmentRule rule) {
    WorldSettings settings;
    settings.pipeline = Pipeline::paper_lists;
    settings.segment_rule = rule;
    settings.profile = true;  // for the oversized boxes' count
    return settings;
}

/// Grains of side 0.2 to 1 in a cube of side 20, with a few rods of length 8 among them: far
/// longer than a segment cut by counts (about 2.3 here), so the counts make them oversized.
struct Scene {
    std::vector<BoxId> ids;
    std::vector<Box3d> boxes;
    BoxId next_id = 0;

    Box3d make(Random& random, bool rod) const {
        Box3d box = random_box<double, 3>(random, 0, 20, 0.2, 1);
        if (rod) box.max[static_cast<std::size_t>(next_id % 3)] += 8;
        return box;
    }
    void add(Random& random) {
        boxes.push_back(make(random, next_id % 500 == 0));
        ids.push_back(next_id++);
    }
};

/// Steps of the scene in `world` against brute force; returns the largest number of oversized
/// boxes any detection reported.
std::size_t run_against_brute_force(World3d& world, std::uint64_t seed) {
    Random random(seed);
    Scene scene;
    for (int i = 0; i < 3000; ++i) scene.add(random);
    world.insert(scene.ids, scene.boxes);
    std::size_t most_oversized = 0;
    std::vector<Pair> pairs;
    for (int step = 0; step < 6; ++step) {
        if (step > 0) {
            for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
                // Most boxes drift; one in fifty jumps across the cube (a teleport).
                scene.boxes[i] = chance(random, 0.02) ? scene.make(random, scene.ids[i] % 500 == 0)
                                                      : perturbed<double, 3>(random, scene.boxes[i], 0.2, 0.05);
            }
            world.update(scene.ids, scene.boxes);
            for (int r = 0; r < 60; ++r) {  // departures, swapped out of the arrays
                const std::size_t at = uniform_index(random, scene.ids.size());
                world.remove(scene.ids[at]);
                scene.ids[at] = scene.ids.back();
                scene.boxes[at] = scene.boxes.back();
                scene.ids.pop_back();
                scene.boxes.pop_back();
            }
            const std::size_t before = scene.ids.size();
            for (int a = 0; a < 80; ++a) scene.add(random);
            world.insert(std::span<const BoxId>(scene.ids).subspan(before),
                         std::span<const Box3d>(scene.boxes).subspan(before));
        }
        world.detect(pairs);
        most_oversized = std::max(most_oversized, world.last_profile().oversized_boxes);
        EXPECT_TRUE(same_pairs(pairs, brute_force_pairs<double, 3>(scene.ids, scene.boxes)))
            << "seed " << seed << ", step " << step;
    }
    return most_oversized;
}

TEST(PaperSegmentRule, NoBoxIsOversizedAndThePairsAreExact) {
    for (const std::uint64_t seed : {11U, 12U}) {
        World3d counts(paper_settings(SegmentRule::from_count));
        World3d paper(paper_settings(SegmentRule::twice_largest_box));
        EXPECT_GT(run_against_brute_force(counts, seed), 0U) << "the rods should span three segments by counts";
        EXPECT_EQ(run_against_brute_force(paper, seed), 0U);
    }
}

TEST(PaperSegmentRule, OneHugeBoxMakesOneCellAndStaysExact) {
    // A floor as wide as the scene: the rule forbids every cut, as the paper's remark 4 warns.
    World2d world(paper_settings(SegmentRule::twice_largest_box));
    Random random(5);
    std::vector<BoxId> ids;
    std::vector<Box2d> boxes;
    boxes.push_back(Box2d{{-1, -1}, {41, 0}});
    ids.push_back(0);
    for (BoxId id = 1; id <= 1500; ++id) {
        boxes.push_back(random_box<double, 2>(random, 0, 40, 0.3, 1));
        ids.push_back(id);
    }
    world.insert(ids, boxes);
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_EQ(world.last_profile().oversized_boxes, 0U);
    EXPECT_TRUE(same_pairs(pairs, brute_force_pairs<double, 2>(ids, boxes)));
}

TEST(PaperSegmentRule, SingleBoxAndEqualBoxes) {
    World3f world(paper_settings(SegmentRule::twice_largest_box));
    std::vector<Pair> pairs;
    world.insert(7, Box3f{{0, 0, 0}, {1, 1, 1}});
    world.detect(pairs);
    EXPECT_TRUE(pairs.empty());
    for (BoxId id = 8; id < 108; ++id) world.insert(id, Box3f{{0, 0, 0}, {1, 1, 1}});
    world.detect(pairs);
    EXPECT_EQ(pairs.size(), 101U * 100U / 2U);
}

}  // namespace
}  // namespace smb::test
