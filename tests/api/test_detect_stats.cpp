// SPDX-License-Identifier: MIT
// DetectStats: each phase field means one thing in every pipeline, and is zero where the
// pipeline has no such phase (smb/stats.hpp).

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "smb/smb.hpp"

namespace smb {
namespace {

std::vector<Box3d> random_scene(std::size_t n, unsigned seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> place(0.0, 40.0);
    std::vector<Box3d> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = place(random), y = place(random), z = place(random);
        boxes.push_back(Box3d{{x, y, z}, {x + 1, y + 1, z + 1}});
    }
    return boxes;
}

double phases(const DetectStats& stats) {
    return stats.update_seconds + stats.scan_seconds + stats.containment_seconds + stats.quantile_seconds +
           stats.list_sort_seconds + stats.cut_regroup_seconds + stats.check_seconds;
}

/// A world's build, then a step that removed boxes.
std::pair<DetectStats, DetectStats> world_build_and_removal(Pipeline pipeline) {
    WorldSettings settings;
    settings.pipeline = pipeline;
    World3d world(settings);
    const std::vector<Box3d> boxes = random_scene(20000, 1);
    world.assign(boxes);
    std::vector<Pair> pairs;
    const DetectStats build = world.detect(pairs);
    std::vector<BoxId> doomed;
    for (BoxId id = 0; id < 2000; ++id) doomed.push_back(id * 7);
    world.remove(doomed);
    const DetectStats step = world.detect(pairs);
    return {build, step};
}

TEST(DetectStats, PersistentCutsSelectQuantilesAndSortNoLists) {
    const auto [build, step] = world_build_and_removal(Pipeline::persistent_cuts);
    EXPECT_GT(build.quantile_seconds, 0.0) << "the first detection cuts every group";
    EXPECT_GT(build.scan_seconds, 0.0);
    EXPECT_EQ(build.list_sort_seconds, 0.0);
    EXPECT_EQ(build.update_seconds, 0.0) << "nothing to take out";
    EXPECT_EQ(build.containment_seconds, 0.0);
    EXPECT_GT(step.update_seconds, 0.0) << "the removals are taken out";
    EXPECT_EQ(step.list_sort_seconds, 0.0);
    for (const DetectStats& stats : {build, step}) EXPECT_LE(phases(stats), stats.total_seconds);
}

TEST(DetectStats, PaperListsSortListsAndSelectNoQuantiles) {
    const auto [build, step] = world_build_and_removal(Pipeline::paper_lists);
    EXPECT_GT(build.list_sort_seconds, 0.0);
    EXPECT_GT(step.list_sort_seconds, 0.0);
    EXPECT_GT(step.update_seconds, 0.0);
    for (const DetectStats& stats : {build, step}) {
        EXPECT_EQ(stats.quantile_seconds, 0.0);
        EXPECT_EQ(stats.scan_seconds, 0.0) << "the paper's lists hold the boxes as they are";
        EXPECT_EQ(stats.containment_seconds, 0.0);
        EXPECT_EQ(stats.copy_seconds, 0.0);
        EXPECT_LE(phases(stats), stats.total_seconds);
    }
}

// The counts of the paper's lists, level by level: what each level's sort moved and compared,
// which items the regrouping moved to another section; the persistent cuts leave them zero.
TEST(DetectStats, PaperListsCountEachLevelsWork) {
    for (const Pipeline pipeline : {Pipeline::paper_lists, Pipeline::persistent_cuts}) {
        WorldSettings settings;
        settings.pipeline = pipeline;
        World3d world(settings);
        std::vector<Box3d> boxes = random_scene(20000, 3);
        world.assign(boxes);
        std::vector<Pair> pairs;
        world.detect(pairs);
        std::mt19937_64 random(4);
        std::uniform_real_distribution<double> shift(-0.3, 0.3);
        for (Box3d& box : boxes) {
            for (int k = 0; k < 3; ++k) {
                const double by = shift(random);
                box.min[k] += by;
                box.max[k] += by;
            }
        }
        world.assign(boxes);
        const DetectStats step = world.detect(pairs);
        if (pipeline == Pipeline::persistent_cuts) {
            for (int level = 0; level < 3; ++level) {
                EXPECT_EQ(step.level_sort_moves[level] + step.level_sort_comparisons[level] +
                              step.level_singular_items[level] + step.level_sort_fallback_items[level],
                          0U);
            }
            EXPECT_EQ(step.largest_cell_boxes, 0U);
            continue;
        }
        EXPECT_EQ(step.level_sort_moves[0] + step.level_sort_moves[1] + step.level_sort_moves[2], step.sort_moves);
        for (int level = 0; level < 3; ++level) {
            SCOPED_TRACE(::testing::Message() << "level " << level);
            EXPECT_GT(step.level_sort_moves[level], 0U) << "every box moved";
            // One comparison per item per pass at least: 2, 4, 8 items per box on levels 0, 1, 2.
            EXPECT_GE(step.level_sort_comparisons[level], (std::size_t{20000} << (level + 1)) - 16);
            EXPECT_GE(step.level_sort_comparisons[level], step.level_sort_moves[level]);
        }
        EXPECT_EQ(step.level_singular_items[0], 0U) << "level 0 is one section";
        EXPECT_GT(step.level_singular_items[1], 0U) << "some boxes crossed a slab's plane";
        EXPECT_GT(step.level_singular_items[2], step.level_singular_items[1]);
        EXPECT_GT(step.largest_cell_boxes, 1U);
    }
}

TEST(DetectStats, DetectorScansItsInputAndHasNoUpdates) {
    for (const double skin : {0.0, 0.1}) {
        DetectorSettings settings;
        settings.skin = skin;
        Detector3d detector(settings);
        std::vector<Box3d> boxes = random_scene(20000, 2);
        std::vector<Pair> pairs;
        const DetectStats build = detector.detect(boxes, pairs);
        for (Box3d& box : boxes) {
            box.min[0] += 0.01;
            box.max[0] += 0.01;
        }
        const DetectStats step = detector.detect(boxes, pairs);
        SCOPED_TRACE(::testing::Message() << "skin " << skin);
        EXPECT_GT(build.quantile_seconds, 0.0);
        for (const DetectStats& stats : {build, step}) {
            EXPECT_EQ(stats.update_seconds, 0.0);
            EXPECT_GT(stats.scan_seconds, 0.0);
            EXPECT_EQ(stats.list_sort_seconds, 0.0);
            EXPECT_LE(phases(stats), stats.total_seconds);
        }
        // With a skin, the step after the build checks every box against its fat box.
        if (skin > 0) {
            EXPECT_FALSE(step.skin_rebuilt);
            EXPECT_GT(step.containment_seconds, 0.0);
        } else {
            EXPECT_EQ(step.containment_seconds, 0.0);
        }
    }
}

}  // namespace
}  // namespace smb
