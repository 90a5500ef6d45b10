// SPDX-License-Identifier: MIT
// Detector's periodic detection against the brute force over the 3^D images, over many steps:
// random scenes (motion across the boundary, boxes drifting away, teleports, growing and
// shrinking arrays), one and two threads, with and without the skin; no periodic axis; a pair
// that crosses the boundary staying one contact for the events. The fixed scenes at the boundary
// and rejected input are in tests/api/test_periodic_detector_edges.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "reference/periodic_brute_force.hpp"
#include "reference/periodic_detector_test.hpp"
#include "reference/world_types.hpp"
#include "smb/detector.hpp"

namespace smb::test {
namespace {

TYPED_TEST_SUITE(PeriodicDetectorTest, Shapes, ShapeNames);

TYPED_TEST(PeriodicDetectorTest, RandomScenesOverManyStepsMatchBruteForce) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    const double side = 20;
    const unsigned all = (1u << Dim) - 1;
    for (const unsigned axes : {all, 1u, all & ~1u}) {
        Random random(1000 + axes);
        const auto domain = cube_domain<Real, Dim>(side, axes);
        std::vector<Box<Real, Dim>> boxes;
        for (std::size_t i = 0; i < scaled(250); ++i)
            boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, Dim == 2 ? 2.5 : 4.0));
        DetectorSettings one;
        DetectorSettings two;
        two.threads = 2;
        two.target_cell_population = 6;  // more cells, so that two threads share the work
        DetectorSettings skin;
        skin.skin = 0.5;
        Detector<Real, Dim> detector(one);
        Detector<Real, Dim> threaded(two);
        Detector<Real, Dim> skinned(skin);
        std::vector<PeriodicPair> pairs;
        std::vector<PeriodicPair> pairs_threaded;
        std::vector<PeriodicPair> pairs_skinned;
        for (int step = 0; step < 12; ++step) {
            SCOPED_TRACE("axes " + std::to_string(axes) + ", step " + std::to_string(step));
            detector.detect(boxes, domain, pairs);
            threaded.detect(boxes, domain, pairs_threaded);
            skinned.detect(boxes, domain, pairs_skinned);
            const auto expected = brute(boxes, domain);
            ASSERT_TRUE(same_periodic_pairs(pairs, expected));
            ASSERT_TRUE(same_periodic_pairs(pairs_skinned, expected));
            // Two threads over other cells: the same pairs; one thread twice: the same order.
            ASSERT_TRUE(same_periodic_pairs(pairs_threaded, expected));
            EXPECT_EQ(detector.last_stats().pairs, expected.size());
            for (auto& box : boxes) box = moved(random, box, domain, 0.3, chance(random, 0.05));
            if (step % 6 == 3) {  // teleports, some several periods away
                for (int t = 0; t < 10; ++t) {
                    auto& box = boxes[uniform_index(random, boxes.size())];
                    box = translated(particle_box<Real, Dim>(random, side, 0.2, 2.0), domain,
                                     static_cast<int>(uniform_index(random, 7)) - 3);
                }
            }
            if (step % 4 == 1) boxes.resize(boxes.size() - boxes.size() / 8);  // shrink
            if (step % 4 == 2) {                                               // grow
                for (int g = 0; g < 40; ++g) boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, 2.0));
            }
        }
    }
}

TYPED_TEST(PeriodicDetectorTest, TheSkinKeepsCandidatesAcrossTheBoundary) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    Random random(31);
    const double side = 16;
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(400); ++i) boxes.push_back(particle_box<Real, Dim>(random, side, 0.3, 1.5));
    DetectorSettings settings;
    settings.skin = 0.3;
    Detector<Real, Dim> detector(settings);
    std::vector<PeriodicPair> pairs;
    std::size_t with_candidates = 0;
    for (int step = 0; step < 30; ++step) {
        detector.detect(boxes, domain, pairs);
        ASSERT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain))) << "step " << step;
        with_candidates += detector.last_stats().skin_candidates > 0 ? 1 : 0;
        // Small steps, the centres wrapped: boxes cross the boundary under the skin.
        for (auto& box : boxes) box = moved(random, box, domain, 0.03, false);
        if (step % 10 == 5) boxes.pop_back();
    }
    EXPECT_GT(with_candidates, 20u) << "the skin list did not detect";
}

TYPED_TEST(PeriodicDetectorTest, EmptyArrays) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    const auto domain = cube_domain<Real, Dim>(4, 1);
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs{PeriodicPair{1, 2, {}}};
    detector.detect(std::span<const Box<Real, Dim>>{}, domain, pairs);
    EXPECT_TRUE(pairs.empty());
    std::vector<Box<Real, Dim>> one(1);
    detector.detect(one, domain, pairs);
    EXPECT_TRUE(pairs.empty());
}

TYPED_TEST(PeriodicDetectorTest, ThreadCountGivesTheSamePairsInTheSameOrder) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    Random random(7);
    const double side = 30;
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(3000); ++i) boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, 2.0));
    DetectorSettings two;
    two.threads = 2;
    Detector<Real, Dim> single;
    Detector<Real, Dim> threaded(two);
    std::vector<PeriodicPair> a;
    std::vector<PeriodicPair> b;
    for (int step = 0; step < 5; ++step) {
        single.detect(boxes, domain, a);
        threaded.detect(boxes, domain, b);
        ASSERT_EQ(a, b) << "step " << step;
        for (auto& box : boxes) box = moved(random, box, domain, 0.2, false);
    }
}

TYPED_TEST(PeriodicDetectorTest, WithoutPeriodicAxesItIsTheOrdinaryDetection) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    Random random(21);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(800); ++i) boxes.push_back(particle_box<Real, Dim>(random, 15, 0.2, 30));
    Detector<Real, Dim> detector;
    std::vector<Pair> plain;
    std::vector<PeriodicPair> periodic;
    detector.detect(boxes, plain);
    detector.detect(boxes, PeriodicDomain<Real, Dim>{}, periodic);
    std::vector<PeriodicPair> expected;
    for (const Pair& p : plain) expected.push_back(PeriodicPair{p.a, p.b, {}});
    EXPECT_TRUE(same_periodic_pairs(periodic, expected));
}

TYPED_TEST(PeriodicDetectorTest, APairThatCrossesTheBoundaryStaysOneContact) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    const auto domain = cube_domain<Real, Dim>(10, (1u << Dim) - 1);
    // Two unit boxes side by side travel along x through the boundary, wrapped as a DEM code
    // wraps its particles; a third one stays apart.
    auto at = [](double x, double y) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = Real(k == 0 ? x : y);
            b.max[k] = Real((k == 0 ? x : y) + 1);
        }
        return b;
    };
    auto wrapped = [](double x) { return x >= 10 ? x - 10 : x; };
    Detector<Real, Dim> detector;
    PairEvents events;
    std::vector<PeriodicPair> pairs;
    std::vector<std::array<std::int32_t, 3>> shifts;
    for (int step = 0; step < 24; ++step) {
        const double x = 7 + 0.25 * step;
        const std::vector<Box<Real, Dim>> boxes{at(wrapped(x), 2), at(wrapped(x + 0.75), 2), at(5, 6)};
        detector.detect(boxes, domain, pairs, events);
        ASSERT_EQ(pairs.size(), 1u) << "step " << step;
        EXPECT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain)));
        shifts.push_back(pairs[0].shift);
        if (step == 0) {
            EXPECT_EQ(events.begun().size(), 1u);
        } else {
            EXPECT_TRUE(events.begun().empty()) << "step " << step;
            EXPECT_TRUE(events.ended().empty()) << "step " << step;
        }
    }
    // The shift took more than one value on the way: the pair crossed the boundary.
    EXPECT_NE(std::find(shifts.begin(), shifts.end(), std::array<std::int32_t, 3>{1, 0, 0}), shifts.end());
    EXPECT_NE(std::find(shifts.begin(), shifts.end(), std::array<std::int32_t, 3>{0, 0, 0}), shifts.end());
    const std::vector<Box<Real, Dim>> apart{at(1, 2), at(5, 2), at(5, 6)};
    detector.detect(apart, domain, pairs, events);
    EXPECT_TRUE(pairs.empty());
    EXPECT_EQ(events.ended().size(), 1u);
}

}  // namespace
}  // namespace smb::test
