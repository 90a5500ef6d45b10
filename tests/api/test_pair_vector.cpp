// SPDX-License-Identifier: MIT
// detect(..., std::vector<Pair>&) of World and Detector: on success the vector holds exactly
// the detection's pairs, whatever it held before; when the call throws (an invalid box, the
// pair limit) it holds what it held before, element for element.

#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "reference/brute_force.hpp"
#include "smb/smb.hpp"

namespace smb {
namespace {

/// What a caller's vector might hold from an earlier step.
const std::vector<Pair> kOldPairs{{1, 2}, {3, 4}, {5, 9}, {7, 8}};

std::vector<Box3d> grid_of_touching_boxes(std::size_t side) {
    std::vector<Box3d> boxes;
    for (std::size_t i = 0; i < side * side; ++i) {
        const double x = static_cast<double>(i % side), y = static_cast<double>(i / side);
        boxes.push_back(Box3d{{x, y, 0}, {x + 1, y + 1, 1}});
    }
    return boxes;
}

TEST(PairVector, WorldReplacesWhatTheVectorHeld) {
    for (const Pipeline pipeline : {Pipeline::persistent_cuts, Pipeline::paper_lists}) {
        WorldSettings settings;
        settings.pipeline = pipeline;
        settings.pair_chunk_size = 7;
        World3d world(settings);
        const std::vector<Box3d> boxes = grid_of_touching_boxes(12);
        world.assign(boxes);
        std::vector<Pair> pairs = kOldPairs;
        world.detect(pairs);
        sort_pairs(pairs);
        EXPECT_EQ(pairs, (test::brute_force_pairs<double, 3>(std::span<const Box3d>(boxes))));
    }
}

TEST(PairVector, DetectorReplacesWhatTheVectorHeld) {
    for (const double skin : {0.0, 0.1}) {
        DetectorSettings settings;
        settings.skin = skin;
        Detector3d detector(settings);
        const std::vector<Box3d> boxes = grid_of_touching_boxes(12);
        for (int call = 0; call < 3; ++call) {
            std::vector<Pair> pairs = kOldPairs;
            detector.detect(boxes, pairs);
            sort_pairs(pairs);
            EXPECT_EQ(pairs, (test::brute_force_pairs<double, 3>(std::span<const Box3d>(boxes)))) << "skin " << skin;
        }
    }
}

TEST(PairVector, WorldPastThePairLimitLeavesTheVectorAsItWas) {
    for (const Pipeline pipeline : {Pipeline::persistent_cuts, Pipeline::paper_lists}) {
        WorldSettings settings;
        settings.pipeline = pipeline;
        settings.max_pairs_held = 100;
        settings.pair_chunk_size = 16;
        World3d world(settings);
        world.assign(std::vector<Box3d>(60, Box3d{{0, 0, 0}, {1, 1, 1}}));  // 1770 pairs
        std::vector<Pair> pairs = kOldPairs;
        EXPECT_THROW(world.detect(pairs), PairLimitError);
        EXPECT_EQ(pairs, kOldPairs);
        EXPECT_LE(pairs.capacity(), 64U) << "the refused pairs' memory is given back";
    }
}

TEST(PairVector, DetectorPastThePairLimitOrOnAnInvalidBoxLeavesTheVectorAsItWas) {
    for (const double skin : {0.0, 0.1}) {
        DetectorSettings settings;
        settings.skin = skin;
        settings.max_pairs_held = 100;
        settings.pair_chunk_size = 16;
        Detector3d detector(settings);
        std::vector<Pair> pairs = kOldPairs;
        const std::vector<Box3d> same(60, Box3d{{0, 0, 0}, {1, 1, 1}});  // 1770 pairs
        EXPECT_THROW(detector.detect(same, pairs), PairLimitError);
        EXPECT_EQ(pairs, kOldPairs);
        EXPECT_LE(pairs.capacity(), 64U) << "the refused pairs' memory is given back";

        std::vector<Box3d> boxes = grid_of_touching_boxes(5);  // 72 pairs
        detector.detect(boxes, pairs);                         // cuts (and candidates) to keep
        pairs = kOldPairs;
        boxes[17].max[1] = boxes[17].min[1] - 1;
        EXPECT_THROW(detector.detect(boxes, pairs), InvalidBoxError);
        EXPECT_EQ(pairs, kOldPairs);
    }
}

}  // namespace
}  // namespace smb
