// SPDX-License-Identifier: MIT
// The grid pair finder used by `smb run` as its independent reference, checked pair for pair
// against the O(n^2) brute force on random and awkward scenes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "reference/brute_force.hpp"
#include "smb/workload/reference_grid.hpp"

namespace smb::workload {
namespace {

using test::brute_force_pairs;

template <typename Real, int Dim>
struct Scene {
    std::vector<BoxId> ids;
    std::vector<Box<Real, Dim>> boxes;

    void add(const Box<Real, Dim>& box) {
        // Ids deliberately not in box order, to catch a < b mistakes.
        ids.push_back(1000003 * (ids.size() + 1) % 1000033);
        boxes.push_back(box);
    }
};

template <typename Real, int Dim>
Box<Real, Dim> random_box(std::mt19937_64& rng, double space, double min_side, double max_side) {
    std::uniform_real_distribution<double> position(-space / 2, space / 2);
    std::uniform_real_distribution<double> side(min_side, max_side);
    Box<Real, Dim> box;
    for (int k = 0; k < Dim; ++k) {
        box.min[k] = static_cast<Real>(position(rng));
        box.max[k] = static_cast<Real>(box.min[k] + side(rng));
    }
    return box;
}

template <typename Real, int Dim>
void expect_matches_brute_force(const Scene<Real, Dim>& scene) {
    const std::span<const BoxId> ids(scene.ids);
    const std::span<const Box<Real, Dim>> boxes(scene.boxes);
    EXPECT_EQ(grid_pairs(ids, boxes), brute_force_pairs(ids, boxes));
}

template <typename Real, int Dim>
void check_random_scenes(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    for (const double space : {5.0, 20.0, 200.0}) {
        Scene<Real, Dim> scene;
        for (int i = 0; i < 1500; ++i) scene.add(random_box<Real, Dim>(rng, space, 0.1, 1.0));
        expect_matches_brute_force(scene);
    }
}

TEST(ReferenceGrid, RandomScenes2dDouble) { check_random_scenes<double, 2>(1); }
TEST(ReferenceGrid, RandomScenes3dDouble) { check_random_scenes<double, 3>(2); }
TEST(ReferenceGrid, RandomScenes2dFloat) { check_random_scenes<float, 2>(3); }
TEST(ReferenceGrid, RandomScenes3dFloat) { check_random_scenes<float, 3>(4); }

TEST(ReferenceGrid, EmptyAndSingleScenes) {
    Scene<double, 3> scene;
    expect_matches_brute_force(scene);
    scene.add({{0, 0, 0}, {1, 1, 1}});
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, TouchingBoxesOnALatticeOverlap) {
    // Unit boxes on a unit lattice touch their 26 neighbours: every touch is a contact, and
    // every corner lies exactly on a cell boundary.
    Scene<double, 3> scene;
    for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 6; ++y)
            for (int z = 0; z < 6; ++z) scene.add({{double(x), double(y), double(z)}, {x + 1.0, y + 1.0, z + 1.0}});
    expect_matches_brute_force(scene);
    // Pairs at Chebyshev distance 1 on a 6^3 lattice: ((6 + 5 + 5)^3 - 6^3) / 2.
    EXPECT_EQ((grid_pairs<double, 3>(scene.ids, scene.boxes).size()), 1940u);
}

TEST(ReferenceGrid, IdenticalBoxesAllOverlap) {
    Scene<double, 2> scene;
    for (int i = 0; i < 50; ++i) scene.add({{1, 1}, {2, 2}});
    expect_matches_brute_force(scene);
    EXPECT_EQ((grid_pairs<double, 2>(scene.ids, scene.boxes).size()), 50u * 49 / 2);
}

TEST(ReferenceGrid, PointBoxesAndZeroExtents) {
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int> coordinate(0, 9);
    Scene<double, 3> scene;
    for (int i = 0; i < 400; ++i) {
        const Box<double, 3> point{{double(coordinate(rng)), double(coordinate(rng)), 0.0}, {0, 0, 0}};
        scene.add({point.min, point.min});
    }
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, OneHugeFloorUnderManyGrains) {
    std::mt19937_64 rng(6);
    Scene<double, 3> scene;
    scene.add({{-100, -100, -1}, {100, 100, 0}});
    for (int i = 0; i < 2000; ++i) scene.add(random_box<double, 3>(rng, 190, 0.5, 1.0));
    scene.add({{-100, -100, 50}, {100, 100, 51}});  // a ceiling that touches nothing
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, HeavyTailedSizesWithManyBigBoxes) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Scene<double, 2> scene;
    for (int i = 0; i < 2000; ++i) {
        const double side = 0.01 / std::pow(1 - 0.999 * unit(rng), 1.5);  // Pareto-like tail
        Box<double, 2> box = random_box<double, 2>(rng, 100, 0, 0);
        box.max = {box.min[0] + side, box.min[1] + side * unit(rng)};
        scene.add(box);
    }
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, LongThinBoxesAlongEachAxis) {
    std::mt19937_64 rng(8);
    Scene<float, 3> scene;
    for (int i = 0; i < 1500; ++i) {
        Box<float, 3> box = random_box<float, 3>(rng, 30, 0.2, 0.4);
        box.max[i % 3] = box.min[i % 3] + 25.0f;
        scene.add(box);
    }
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, TinyBoxesInAHugeSpace) {
    // The cell count must be capped, or the grid would ask for 10^30 cells.
    std::mt19937_64 rng(9);
    Scene<double, 3> scene;
    for (int i = 0; i < 1000; ++i) scene.add(random_box<double, 3>(rng, 1e10, 1e-3, 2e-3));
    scene.add({{0, 0, 0}, {1e-3, 1e-3, 1e-3}});
    scene.add({{1e-3, 1e-3, 1e-3}, {2e-3, 2e-3, 2e-3}});
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, ExtremeCoordinates) {
    const double big = std::numeric_limits<double>::max() / 4;
    Scene<double, 2> scene;
    scene.add({{-big, -big}, {big, big}});
    scene.add({{-big, 0}, {-big, 0}});
    scene.add({{big, big}, {big, big}});
    scene.add({{0, 0}, {1, 1}});
    scene.add({{1, 1}, {2, 2}});
    scene.add({{-0.0, -0.0}, {0.0, 0.0}});
    expect_matches_brute_force(scene);
}

TEST(ReferenceGrid, RejectsBadInput) {
    const std::vector<BoxId> ids{1, 2};
    const std::vector<Box<double, 2>> one_box{{{0, 0}, {1, 1}}};
    EXPECT_THROW((void)(grid_pairs<double, 2>(ids, one_box)), std::invalid_argument);
    const std::vector<Box<double, 2>> inverted{{{0, 0}, {1, 1}}, {{2, 0}, {1, 1}}};
    EXPECT_THROW((void)(grid_pairs<double, 2>(ids, inverted)), std::invalid_argument);
}

}  // namespace
}  // namespace smb::workload
