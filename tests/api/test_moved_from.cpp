// SPDX-License-Identifier: MIT
// A World or Detector that was moved from: empty, holding nothing, with default settings, and
// usable again. Every call on it is valid.

#include <gtest/gtest.h>

#include <span>
#include <utility>
#include <vector>

#include "reference/brute_force.hpp"
#include "smb/smb.hpp"

namespace smb {
namespace {

std::vector<Box3d> touching_row(std::size_t n) {
    std::vector<Box3d> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = static_cast<double>(i);
        boxes.push_back(Box3d{{x, 0, 0}, {x + 1, 1, 1}});  // each touches the next
    }
    return boxes;
}

WorldSettings paper_settings() {
    WorldSettings settings;
    settings.pipeline = Pipeline::paper_lists;
    settings.target_cell_population = 5;
    return settings;
}

/// A world with boxes and a detection behind it, under settings that are not the defaults.
World3d busy_world() {
    World3d world(paper_settings());
    world.assign(touching_row(20));
    std::vector<Pair> pairs;
    world.detect(pairs);
    return world;
}

void expect_empty_with_default_settings(const World3d& world) {
    EXPECT_EQ(world.size(), 0U);
    EXPECT_EQ(world.bytes_held(), 0U);
    EXPECT_FALSE(world.contains(3));
    EXPECT_THROW((void)world.box(3), UnknownIdError);
    EXPECT_EQ(world.settings().pipeline, WorldSettings{}.pipeline);
    EXPECT_EQ(world.settings().target_cell_population, WorldSettings{}.target_cell_population);
    EXPECT_EQ(world.last_stats().pairs, 0U);
    EXPECT_EQ(world.last_precision(), HeldPrecision::none);
    EXPECT_EQ(world.last_retested_pairs(), 0U);
}

TEST(MovedFromWorld, AnswersAsAnEmptyWorldWithDefaultSettings) {
    World3d source = busy_world();
    const World3d target(std::move(source));
    EXPECT_EQ(target.size(), 20U);
    EXPECT_EQ(target.settings().pipeline, Pipeline::paper_lists);
    expect_empty_with_default_settings(source);
}

TEST(MovedFromWorld, ClearIsValid) {
    World3d source = busy_world();
    World3d target = std::move(source);
    source.clear();
    expect_empty_with_default_settings(source);
    EXPECT_EQ(target.size(), 20U);
}

TEST(MovedFromWorld, CanBeAssignedToAndFrom) {
    World3d source = busy_world();
    World3d target = std::move(source);
    World3d other;
    other = std::move(source);  // from a moved-from world
    expect_empty_with_default_settings(other);
    source = std::move(target);  // to a moved-from world
    EXPECT_EQ(source.size(), 20U);
    EXPECT_EQ(source.settings().pipeline, Pipeline::paper_lists);
}

TEST(MovedFromWorld, IsDestroyedAfterEachCall) {
    for (int call = 0; call < 4; ++call) {
        World3d source = busy_world();
        World3d target = std::move(source);
        if (call == 1) source.clear();
        if (call == 2) (void)source.bytes_held();
        if (call == 3) target = std::move(source);
    }  // ASan and the test's survival check the destructors
}

TEST(MovedFromWorld, IsUsableAgainAsANewWorld) {
    World3d source = busy_world();
    World3d target = std::move(source);
    const std::vector<Box3d> boxes = touching_row(6);
    const std::vector<BoxId> ids{0, 1, 2, 3, 4, 5};
    source.insert(std::span<const BoxId>(ids), std::span<const Box3d>(boxes));
    source.update(2, Box3d{{2, 0, 0}, {3, 1, 1}});
    source.remove(5);
    std::vector<Pair> pairs;
    source.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 1}, {1, 2}, {2, 3}, {3, 4}}));
    EXPECT_EQ(source.size(), 5U);
    EXPECT_GT(source.bytes_held(), 0U);
    EXPECT_EQ(source.settings().pipeline, Pipeline::persistent_cuts);

    World3d streamed = std::move(source);
    std::size_t count = 0;
    source.detect([&count](std::span<const Pair> chunk) { count += chunk.size(); });
    EXPECT_EQ(count, 0U);
    source.assign(boxes);
    EXPECT_EQ(source.size(), 6U);
}

/// A detector with cuts and a skin behind it.
Detector3d busy_detector() {
    DetectorSettings settings;
    settings.skin = 0.1;
    settings.target_cell_population = 5;
    Detector3d detector(settings);
    std::vector<Pair> pairs;
    detector.detect(touching_row(40), pairs);
    return detector;
}

void expect_empty_with_default_settings(const Detector3d& detector) {
    EXPECT_EQ(detector.bytes_held(), 0U);
    EXPECT_EQ(detector.settings().skin, DetectorSettings{}.skin);
    EXPECT_EQ(detector.settings().target_cell_population, DetectorSettings{}.target_cell_population);
    EXPECT_EQ(detector.last_stats().pairs, 0U);
    EXPECT_EQ(detector.last_precision(), HeldPrecision::none);
    EXPECT_EQ(detector.last_retested_pairs(), 0U);
}

TEST(MovedFromDetector, AnswersAsANewDetector) {
    Detector3d source = busy_detector();
    const Detector3d target(std::move(source));
    EXPECT_EQ(target.settings().skin, 0.1);
    EXPECT_GT(target.bytes_held(), 0U);
    expect_empty_with_default_settings(source);
}

TEST(MovedFromDetector, ClearAssignmentAndDestructionAreValid) {
    Detector3d source = busy_detector();
    Detector3d target = std::move(source);
    source.clear();
    expect_empty_with_default_settings(source);
    Detector3d other;
    other = std::move(source);  // from a moved-from detector
    expect_empty_with_default_settings(other);
    source = std::move(target);  // to a moved-from detector
    EXPECT_EQ(source.settings().skin, 0.1);
}

TEST(MovedFromDetector, IsUsableAgainAsANewDetector) {
    Detector3d source = busy_detector();
    Detector3d target = std::move(source);
    const std::vector<Box3d> boxes = touching_row(30);
    std::vector<Pair> pairs;
    source.detect(boxes, pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, (test::brute_force_pairs<double, 3>(std::span<const Box3d>(boxes))));
    EXPECT_GT(source.bytes_held(), 0U);

    Detector3d streamed = std::move(source);
    std::size_t count = 0;
    source.detect(boxes, [&count](std::span<const Pair> chunk) { count += chunk.size(); });
    EXPECT_EQ(count, 29U);
}

}  // namespace
}  // namespace smb
