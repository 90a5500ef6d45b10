// SPDX-License-Identifier: MIT
// DetectStats: a few fields, each meaning one thing on every path (smb/stats.hpp). DetectProfile:
// filled only where DetectionSettings::profile asks for it; each phase field means one thing in
// every pipeline, and is zero where the pipeline has no such phase (smb/profile.hpp).

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

void shift_all(std::vector<Box3d>& boxes, double by) {
    for (Box3d& box : boxes) {
        box.min[0] += by;
        box.max[0] += by;
    }
}

/// Every field of a profile, as one sum: zero only where all are.
double profile_sum(const DetectProfile& p) {
    double sum = p.update_seconds + p.scan_seconds + p.containment_seconds + p.quantile_seconds + p.list_sort_seconds +
                 p.cut_regroup_seconds + p.check_seconds + p.copy_seconds +
                 static_cast<double>(p.cells + p.oversized_boxes + p.sort_moves + p.largest_cell_boxes);
    for (std::size_t l = 0; l < 3; ++l) {
        sum += p.level_seconds[l] + static_cast<double>(p.level_sort_moves[l] + p.level_sort_comparisons[l] +
                                                        p.level_singular_items[l] + p.level_sort_fallback_items[l]);
    }
    return sum;
}

double phases(const DetectProfile& profile) {
    return profile.update_seconds + profile.scan_seconds + profile.containment_seconds + profile.quantile_seconds +
           profile.list_sort_seconds + profile.cut_regroup_seconds + profile.check_seconds;
}

/// A profiled world's build, then a step that removed boxes: each one's total seconds and profile.
struct Profiled {
    double total_seconds;
    DetectProfile profile;
};
std::pair<Profiled, Profiled> world_build_and_removal(Pipeline pipeline) {
    WorldSettings settings;
    settings.pipeline = pipeline;
    settings.profile = true;
    World3d world(settings);
    const std::vector<Box3d> boxes = random_scene(20000, 1);
    world.assign(boxes);
    std::vector<Pair> pairs;
    const Profiled build{world.detect(pairs).total_seconds, world.last_profile()};
    std::vector<BoxId> doomed;
    for (BoxId id = 0; id < 2000; ++id) doomed.push_back(id * 7);
    world.remove(doomed);
    const Profiled step{world.detect(pairs).total_seconds, world.last_profile()};
    return {build, step};
}

// Without DetectionSettings::profile the profile stays zero on every path; the stats are there.
TEST(DetectStats, ProfileIsZeroUnlessAsked) {
    const std::vector<Box3d> boxes = random_scene(5000, 5);
    std::vector<Pair> pairs;
    for (const Pipeline pipeline : {Pipeline::persistent_cuts, Pipeline::paper_lists}) {
        WorldSettings settings;
        settings.pipeline = pipeline;
        World3d world(settings);
        world.assign(boxes);
        for (int step = 0; step < 2; ++step) {
            const DetectStats stats = world.detect(pairs);
            EXPECT_EQ(stats.boxes, boxes.size());
            EXPECT_EQ(stats.pairs, pairs.size());
            EXPECT_GT(stats.pairs, 0U);
            EXPECT_EQ(stats.bytes_held, world.bytes_held());
            EXPECT_GT(stats.total_seconds, 0.0);
            EXPECT_EQ(profile_sum(world.last_profile()), 0.0);
        }
    }
    for (const double skin : {0.0, 0.1}) {
        DetectorSettings settings;
        settings.skin = skin;
        Detector3d detector(settings);
        std::vector<Box3d> moving = boxes;
        for (int step = 0; step < 2; ++step) {
            const DetectStats stats = detector.detect(moving, pairs);
            EXPECT_EQ(stats.pairs, pairs.size());
            EXPECT_EQ(stats.bytes_held, detector.bytes_held());
            EXPECT_EQ(profile_sum(detector.last_profile()), 0.0);
            shift_all(moving, 0.01);
        }
    }
    // Asked for, the same detection fills it; clear() forgets it.
    DetectorSettings settings;
    settings.profile = true;
    Detector3d detector(settings);
    detector.detect(boxes, pairs);
    EXPECT_GT(detector.last_profile().check_seconds, 0.0);
    EXPECT_GT(detector.last_profile().cells, 0U);
    detector.clear();
    EXPECT_EQ(profile_sum(detector.last_profile()), 0.0);
}

// The skin's fields are the skin's alone, the statics' fields the statics' alone, whichever
// other part the detection also ran.
TEST(DetectStats, SkinAndStaticsEachHaveTheirOwnFields) {
    const std::vector<Box3d> boxes = random_scene(5000, 6);
    for (const bool statics : {false, true}) {
        for (const double skin : {0.0, 0.1}) {
            SCOPED_TRACE(::testing::Message() << "statics " << statics << ", skin " << skin);
            WorldSettings settings;
            settings.skin = skin;
            World3d world(settings);
            world.assign(boxes);
            if (statics) {
                for (BoxId id = 0; id < 500; ++id) world.set_static(id, true);
            }
            std::vector<Box3d> moving = boxes;
            std::vector<Pair> pairs;
            for (int step = 0; step < 3; ++step) {
                const DetectStats stats = world.detect(pairs);
                EXPECT_EQ(stats.pairs, pairs.size());
                if (skin > 0) {
                    EXPECT_GT(stats.skin_candidates, 0U);
                    EXPECT_EQ(stats.skin_rebuilt, step == 0);
                } else {
                    EXPECT_EQ(stats.skin_candidates + stats.skin_refreshed, 0U);
                    EXPECT_FALSE(stats.skin_rebuilt);
                }
                if (statics) {
                    EXPECT_GT(stats.static_contacts, 0U);
                    EXPECT_EQ(stats.statics_rebuilt, step == 0);
                    if (step == 0) {
                        EXPECT_EQ(stats.static_refreshed, boxes.size() - 500) << "every box arrived";
                    }
                } else {
                    EXPECT_EQ(stats.static_contacts + stats.static_refreshed, 0U);
                    EXPECT_FALSE(stats.statics_rebuilt);
                }
                shift_all(moving, 0.01);
                for (BoxId id = 500; id < moving.size(); ++id) world.update(id, moving[id]);
            }
        }
    }
}

TEST(DetectProfile, PersistentCutsSelectQuantilesAndSortNoLists) {
    const auto [built, stepped] = world_build_and_removal(Pipeline::persistent_cuts);
    const DetectProfile& build = built.profile;
    const DetectProfile& step = stepped.profile;
    EXPECT_GT(build.quantile_seconds, 0.0) << "the first detection cuts every group";
    EXPECT_GT(build.scan_seconds, 0.0);
    EXPECT_EQ(build.list_sort_seconds, 0.0);
    EXPECT_EQ(build.update_seconds, 0.0) << "nothing to take out";
    EXPECT_EQ(build.containment_seconds, 0.0);
    EXPECT_GT(step.update_seconds, 0.0) << "the removals are taken out";
    EXPECT_EQ(step.list_sort_seconds, 0.0);
    for (const Profiled& p : {built, stepped}) EXPECT_LE(phases(p.profile), p.total_seconds);
}

TEST(DetectProfile, PaperListsSortListsAndSelectNoQuantiles) {
    const auto [built, stepped] = world_build_and_removal(Pipeline::paper_lists);
    const DetectProfile& build = built.profile;
    const DetectProfile& step = stepped.profile;
    EXPECT_GT(build.list_sort_seconds, 0.0);
    EXPECT_GT(step.list_sort_seconds, 0.0);
    EXPECT_GT(step.update_seconds, 0.0);
    for (const Profiled& p : {built, stepped}) {
        EXPECT_EQ(p.profile.quantile_seconds, 0.0);
        EXPECT_EQ(p.profile.scan_seconds, 0.0) << "the paper's lists hold the boxes as they are";
        EXPECT_EQ(p.profile.containment_seconds, 0.0);
        EXPECT_EQ(p.profile.copy_seconds, 0.0);
        EXPECT_LE(phases(p.profile), p.total_seconds);
    }
}

// The counts of the paper's lists, level by level: what each level's sort moved and compared,
// which items the regrouping moved to another section; the persistent cuts leave them zero.
TEST(DetectProfile, PaperListsCountEachLevelsWork) {
    for (const Pipeline pipeline : {Pipeline::paper_lists, Pipeline::persistent_cuts}) {
        WorldSettings settings;
        settings.pipeline = pipeline;
        settings.profile = true;
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
        world.detect(pairs);
        const DetectProfile step = world.last_profile();
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

TEST(DetectProfile, DetectorScansItsInputAndHasNoUpdates) {
    for (const double skin : {0.0, 0.1}) {
        DetectorSettings settings;
        settings.skin = skin;
        settings.profile = true;
        Detector3d detector(settings);
        std::vector<Box3d> boxes = random_scene(20000, 2);
        std::vector<Pair> pairs;
        const Profiled build{detector.detect(boxes, pairs).total_seconds, detector.last_profile()};
        shift_all(boxes, 0.01);
        const DetectStats step_stats = detector.detect(boxes, pairs);
        const Profiled step{step_stats.total_seconds, detector.last_profile()};
        SCOPED_TRACE(::testing::Message() << "skin " << skin);
        EXPECT_GT(build.profile.quantile_seconds, 0.0);
        for (const Profiled& p : {build, step}) {
            EXPECT_EQ(p.profile.update_seconds, 0.0);
            EXPECT_GT(p.profile.scan_seconds, 0.0);
            EXPECT_EQ(p.profile.list_sort_seconds, 0.0);
            EXPECT_LE(phases(p.profile), p.total_seconds);
        }
        // With a skin, the step after the build checks every box against its fat box.
        if (skin > 0) {
            EXPECT_FALSE(step_stats.skin_rebuilt);
            EXPECT_GT(step.profile.containment_seconds, 0.0);
        } else {
            EXPECT_EQ(step.profile.containment_seconds, 0.0);
        }
    }
}

}  // namespace
}  // namespace smb
