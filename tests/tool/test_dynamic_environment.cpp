// SPDX-License-Identifier: MIT
// The paper's artificial dynamic environment: determinism, the λ rule for N, valid boxes inside
// the cube, E and H at step 0, and the hand-over of steps to a World.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/world_sync.hpp"
#include "smb/world.hpp"

namespace smb::workload {
namespace {

EnvironmentParams small_params(std::size_t box_count, double update_factor, std::uint64_t seed) {
    EnvironmentParams params;
    params.box_count = box_count;
    params.packing_density = 0.4;
    params.size_ratio = 2.5;
    params.update_factor = update_factor;
    params.seed = seed;
    return params;
}

template <int Dim>
void expect_inside_cube(const DynamicEnvironment<Dim>& env) {
    for (const auto& box : env.boxes()) {
        ASSERT_TRUE(is_valid(box));
        for (int k = 0; k < Dim; ++k) {
            ASSERT_GE(box.min[k], 0.0);
            ASSERT_LE(box.max[k], env.cube_side());
            // The walls may shave a last bit off a side, nothing more.
            ASSERT_GE(box.max[k] - box.min[k], env.min_side() * (1 - 1e-12));
            ASSERT_LE(box.max[k] - box.min[k], env.max_side() * (1 + 1e-12));
        }
    }
}

TEST(DynamicEnvironment, SameSeedGivesSameScene) {
    DynamicEnvironment<3> first(small_params(3000, 0.05, 7));
    DynamicEnvironment<3> second(small_params(3000, 0.05, 7));
    for (int step = 0; step < 5; ++step) {
        first.step();
        second.step();
    }
    ASSERT_TRUE(std::ranges::equal(first.ids(), second.ids()));
    ASSERT_TRUE(std::ranges::equal(first.boxes(), second.boxes()));
}

TEST(DynamicEnvironment, DifferentSeedsGiveDifferentScenes) {
    DynamicEnvironment<3> first(small_params(100, 1e-3, 1));
    DynamicEnvironment<3> second(small_params(100, 1e-3, 2));
    EXPECT_FALSE(std::ranges::equal(first.boxes(), second.boxes()));
}

TEST(DynamicEnvironment, StepZeroHonoursDensityAndSizeRatio) {
    const std::size_t n = 20000;
    DynamicEnvironment<3> env(small_params(n, 1e-3, 3));
    EXPECT_EQ(env.size(), n);
    EXPECT_DOUBLE_EQ(env.max_side(), 1.0);
    EXPECT_DOUBLE_EQ(env.min_side(), 0.4);
    EXPECT_DOUBLE_EQ(env.packing_density(), 0.4);
    // E = N ((a + b) / 2)^3 / x^3 by the paper's definition.
    EXPECT_NEAR(static_cast<double>(n) * std::pow(0.7 / env.cube_side(), 3), 0.4, 1e-12);
    double side_sum = 0;
    for (const auto& box : env.boxes())
        for (int k = 0; k < 3; ++k) side_sum += box.max[k] - box.min[k];
    EXPECT_NEAR(side_sum / (3.0 * n), 0.7, 0.01);
    expect_inside_cube(env);
}

TEST(DynamicEnvironment, CubeSideGivenDerivesDensity) {
    EnvironmentParams params = small_params(1000, 1e-3, 1);
    params.cube_side = 20.0;
    DynamicEnvironment<2> env(params);
    EXPECT_DOUBLE_EQ(env.cube_side(), 20.0);
    EXPECT_NEAR(env.packing_density(), 1000 * 0.7 * 0.7 / 400.0, 1e-12);
    expect_inside_cube(env);
}

TEST(DynamicEnvironment, StepZeroIsReportedAsInsertions) {
    DynamicEnvironment<2> env(small_params(50, 1e-3, 1));
    const auto& changes = env.changes();
    EXPECT_TRUE(changes.removed_ids.empty());
    EXPECT_TRUE(changes.updated_ids.empty());
    ASSERT_EQ(changes.inserted_ids.size(), 50u);
    for (std::size_t i = 0; i < 50; ++i) EXPECT_EQ(changes.inserted_ids[i], i);
}

TEST(DynamicEnvironment, CountFollowsTheLambdaRule) {
    const double update_factor = 0.1;
    DynamicEnvironment<3> env(small_params(2000, update_factor, 11));
    bool grew = false;
    bool shrank = false;
    for (int step = 0; step < 40; ++step) {
        const std::size_t before = env.size();
        const BoxId next_fresh = env.ids().empty() ? 0 : env.ids().back() + 1;
        const auto& changes = env.step();
        const auto bound = std::llround(update_factor * static_cast<double>(before));
        const auto removed = static_cast<long long>(changes.removed_ids.size());
        const auto inserted = static_cast<long long>(changes.inserted_ids.size());
        ASSERT_TRUE(removed == 0 || inserted == 0);
        ASSERT_LE(removed, bound);
        ASSERT_LE(inserted, bound);
        ASSERT_EQ(env.size(), before - changes.removed_ids.size() + changes.inserted_ids.size());
        ASSERT_EQ(changes.updated_ids.size(), before - changes.removed_ids.size());
        for (const BoxId id : changes.inserted_ids) ASSERT_GE(id, next_fresh);
        grew = grew || inserted > 0;
        shrank = shrank || removed > 0;
        ASSERT_TRUE(std::ranges::is_sorted(env.ids()));
        ASSERT_TRUE(std::ranges::adjacent_find(env.ids()) == env.ids().end());
    }
    EXPECT_TRUE(grew);
    EXPECT_TRUE(shrank);
}

TEST(DynamicEnvironment, RemovedIdsWereAliveAndAreGone) {
    DynamicEnvironment<2> env(small_params(1000, 0.2, 5));
    for (int step = 0; step < 20; ++step) {
        const std::vector<BoxId> before(env.ids().begin(), env.ids().end());
        const auto& changes = env.step();
        for (const BoxId id : changes.removed_ids) {
            ASSERT_TRUE(std::ranges::binary_search(before, id));
            ASSERT_FALSE(std::ranges::binary_search(env.ids(), id));
        }
    }
}

TEST(DynamicEnvironment, MotionIsBoundedByTheUpdateFactorAndStaysInside) {
    const double update_factor = 0.05;
    DynamicEnvironment<3> env(small_params(3000, update_factor, 9));
    for (int step = 0; step < 30; ++step) {
        std::map<BoxId, Box<double, 3>> before;
        for (std::size_t i = 0; i < env.size(); ++i) before[env.ids()[i]] = env.boxes()[i];
        const auto& changes = env.step();
        for (std::size_t i = 0; i < changes.updated_ids.size(); ++i) {
            const auto& old_box = before.at(changes.updated_ids[i]);
            const auto& new_box = changes.updated_boxes[i];
            for (int k = 0; k < 3; ++k) {
                const double old_side = old_box.max[k] - old_box.min[k];
                const double new_side = new_box.max[k] - new_box.min[k];
                const double centre_shift =
                    (new_box.min[k] + new_box.max[k]) / 2 - (old_box.min[k] + old_box.max[k]) / 2;
                ASSERT_LE(std::abs(new_side - old_side), update_factor * 1.0 + 1e-9);
                // At a wall the reflection bound itself moves with half the side change.
                ASSERT_LE(std::abs(centre_shift), update_factor * (env.cube_side() + 1.0) + 1e-9);
            }
        }
        expect_inside_cube(env);
    }
}

TEST(DynamicEnvironment, ReflectionKeepsTinyCubesValid) {
    // A cube barely larger than the largest box forces reflections at every wall.
    EnvironmentParams params = small_params(200, 0.5, 13);
    params.cube_side = 1.05;
    params.size_ratio = 10;
    DynamicEnvironment<2> env(params);
    for (int step = 0; step < 50; ++step) {
        env.step();
        expect_inside_cube(env);
    }
}

TEST(DynamicEnvironment, ZeroUpdateFactorKeepsEverythingStill) {
    DynamicEnvironment<3> env(small_params(500, 0.0, 1));
    const std::vector<Box<double, 3>> before(env.boxes().begin(), env.boxes().end());
    env.step();
    EXPECT_EQ(env.size(), 500u);
    EXPECT_TRUE(std::ranges::equal(env.boxes(), before));
}

TEST(DynamicEnvironment, RejectsParametersOutOfRange) {
    auto with = [](auto change) {
        EnvironmentParams params = small_params(1000, 1e-3, 1);
        change(params);
        return params;
    };
    EXPECT_THROW(DynamicEnvironment<3>(with([](auto& p) { p.packing_density = 0; })), std::invalid_argument);
    EXPECT_THROW(DynamicEnvironment<3>(with([](auto& p) { p.size_ratio = 0.5; })), std::invalid_argument);
    EXPECT_THROW(DynamicEnvironment<3>(with([](auto& p) { p.update_factor = 1.0; })), std::invalid_argument);
    EXPECT_THROW(DynamicEnvironment<3>(with([](auto& p) { p.update_factor = -0.1; })), std::invalid_argument);
    EXPECT_THROW(DynamicEnvironment<3>(with([](auto& p) { p.cube_side = 0.5; })), std::invalid_argument);
}

template <typename Real, int Dim>
void expect_world_follows_environment() {
    DynamicEnvironment<Dim> env(small_params(800, 0.05, 21));
    World<Real, Dim> world;
    apply_changes(env.changes(), world);
    for (int step = 0; step < 10; ++step) apply_changes(env.step(), world);
    ASSERT_EQ(world.size(), env.size());
    const auto converted = convert_boxes<Real>(env.boxes());
    for (std::size_t i = 0; i < env.size(); ++i) ASSERT_EQ(world.box(env.ids()[i]), converted[i]);
}

TEST(WorldSync, DoubleWorldFollowsEnvironment) { expect_world_follows_environment<double, 3>(); }
TEST(WorldSync, FloatWorldFollowsEnvironment) { expect_world_follows_environment<float, 2>(); }

}  // namespace
}  // namespace smb::workload
