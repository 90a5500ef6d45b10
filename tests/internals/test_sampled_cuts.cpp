// SPDX-License-Identifier: MIT
// The first detection's path (src/cuts/sampled_cuts.hpp, CellOrder::copy_by_column): the levels
// above the columns cut from a sample of the input, every group's planes in order and its band
// set; the boxes copied once each, grouped by column, in slot order within a column, on one
// thread or several; and first detections (and those after a change of the number of segments,
// which start again without planes) exact against brute force on lattices of equal coordinates,
// touching boxes, points and boxes across many segments, float and double, 2D and 3D; and a
// layer a few boxes thick, whose level gives the segments it cannot open to the other level (or,
// a box or two thick, all of them).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "core/tuning.hpp"
#include "cuts/cell_order.hpp"
#include "cuts/cut_tree.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "cuts/sampled_cuts.hpp"
#include "internals/pipeline_pairs.hpp"
#include "reference/brute_force.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {
namespace {

/// Boxes on an integer lattice of `side` places per axis, each 0 to 2 places wide (so points,
/// touching boxes and runs of equal coordinates), and every 97th box `wide` places wide.
template <class Real, int Dim>
std::vector<Box<Real, Dim>> lattice_boxes(std::size_t n, int side, int wide, std::mt19937_64& random) {
    std::uniform_int_distribution<int> place(0, side - 1);
    std::uniform_int_distribution<int> extent(0, 2);
    std::vector<Box<Real, Dim>> boxes(n);
    for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < Dim; ++k) {
            boxes[i].min[k] = static_cast<Real>(place(random));
            boxes[i].max[k] = boxes[i].min[k] + static_cast<Real>(i % 97 == 5 ? wide : extent(random));
        }
    }
    return boxes;
}

TEST(SampledCuts, CutsEveryGroupAboveTheColumnsInOrderAndSetsItsBand) {
    std::mt19937_64 random(31);
    // Enough boxes that the sample is a part of them (256 keys per segment of each group).
    const std::vector<Box<float, 3>> boxes = lattice_boxes<float, 3>(20000, 40, 9, random);
    CutTree<float, 3> cuts;
    cuts.reshape(3);
    SampledCuts<float, 3, float> sampled;
    sampled.cut(boxes, {}, cuts);
    for (int level = 0; level < 2; ++level) {
        for (std::size_t group = 0; group < cuts.groups(level); ++group) {
            SCOPED_TRACE(testing::Message() << "level " << level << " group " << group);
            EXPECT_TRUE(cuts.was_cut(level, group));
            const std::span<const float> planes = cuts.cuts(level, group);
            EXPECT_TRUE(std::is_sorted(planes.begin(), planes.end()));
            // Not cut again by the levels unless a segment outgrows twice its even share.
            EXPECT_FALSE(cuts.needs_cut(level, group, 0));
        }
    }
    for (std::size_t group = 0; group < cuts.groups(2); ++group) EXPECT_FALSE(cuts.was_cut(2, group));
}

TEST(SampledCuts, CopyByColumnCopiesEverySlotOnceGroupedByColumn) {
    std::mt19937_64 random(32);
    const std::vector<Box<double, 3>> boxes = lattice_boxes<double, 3>(5000, 30, 6, random);
    const std::array<double, 3> origin{15.0, -3.0, 0.5};
    CutTree<float, 3> cuts;
    cuts.reshape(4);
    SampledCuts<float, 3, double> sampled;
    sampled.cut(boxes, origin, cuts);
    // Ids held in 32 bits, and ids that need 64 (the first past 2^32: the copy widens them all).
    for (const BoxId first : {BoxId{1000}, (BoxId{1} << 32) - 7 * 2500})
        for (const int threads : {1, 3}) {
            SCOPED_TRACE(first);
            SCOPED_TRACE(threads);
            std::vector<BoxId> ids(boxes.size());
            for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = first + 7 * i;
            CellOrder<float, 3, double> order;
            order.list_arrivals(boxes.size());
            order.copy_by_column(
                boxes, ids, origin, cuts.groups(2), [&](const Box<float, 3>& box) { return cuts.column_of(box); },
                threads);
            ASSERT_EQ(order.wide(), first != 1000);
            const std::span<const Slot> slots = order.order();
            ASSERT_EQ(slots.size(), boxes.size());
            std::vector<bool> seen(boxes.size(), false);
            for (std::size_t i = 0; i < slots.size(); ++i) {
                ASSERT_LT(slots[i], boxes.size());
                ASSERT_FALSE(seen[slots[i]]) << "slot " << slots[i] << " twice";
                seen[slots[i]] = true;
                const Box<float, 3> held = held_box<double, 3>(boxes[slots[i]], origin);
                for (int k = 0; k < 3; ++k) {
                    ASSERT_EQ(order.boxes()[i].min[k], held.min[k]);
                    ASSERT_EQ(order.boxes()[i].max[k], held.max[k]);
                }
                ASSERT_EQ(order.id_at(static_cast<Position>(i)), ids[slots[i]]);
                if (i == 0) continue;
                const std::uint32_t before = cuts.column_of(order.boxes()[i - 1]);
                const std::uint32_t here = cuts.column_of(order.boxes()[i]);
                ASSERT_LE(before, here) << "at " << i;
                if (before == here) {
                    ASSERT_LT(slots[i - 1], slots[i]) << "at " << i;
                }
            }
        }
}

/// Boxes of sides 0.4 to 1 in a layer `thickness` deep on axis `thin` and 100 wide on the others.
std::vector<Box<float, 3>> layer_boxes(std::size_t n, int thin, float thickness, std::mt19937_64& random) {
    std::uniform_real_distribution<float> unit(0.0F, 1.0F);
    std::vector<Box<float, 3>> boxes(n);
    for (Box<float, 3>& box : boxes) {
        for (int k = 0; k < 3; ++k) {
            box.min[k] = unit(random) * (k == thin ? thickness : 100.0F);
            box.max[k] = box.min[k] + 0.4F + 0.6F * unit(random);
        }
    }
    return boxes;
}

/// A layer a few boxes thick on the axis of level `layer` keeps the segments it can open there,
/// and the other level above the columns takes the rest, as many columns as before; a layer
/// about two boxes thick, whose segments would each be about a box thick, is left whole.
void check_layer_shape(int layer) {
    std::mt19937_64 random(51 + layer);
    for (const float thickness : {2.0F, 6.5F}) {
        const std::vector<Box<float, 3>> boxes = layer_boxes(20000, 2 - layer, thickness, random);
        CutTree<float, 3> cuts;
        cuts.reshape(12);
        SampledCuts<float, 3, float>().cut(boxes, {}, cuts);
        if (thickness < 3.0F) {
            EXPECT_EQ(cuts.segments(layer), 1U) << "left whole";
        } else {
            EXPECT_GT(cuts.segments(layer), static_cast<std::uint32_t>(tuning::whole_layer_open)) << thickness;
            EXPECT_LT(cuts.segments(layer), 9U) << "a layer: fewer than three quarters of 12 open";
        }
        const double columns = static_cast<double>(cuts.segments(0)) * cuts.segments(1);
        EXPECT_NEAR(columns, 144.0, 0.5 * cuts.segments(layer));
        EXPECT_EQ(cuts.segments(2), 12U);
        for (int level = 0; level < 2; ++level) {
            for (std::size_t group = 0; group < cuts.groups(level); ++group) EXPECT_TRUE(cuts.was_cut(level, group));
        }
    }
    // Boxes that fill the cube keep the shape they were given.
    CutTree<float, 3> cube;
    cube.reshape(12);
    SampledCuts<float, 3, float>().cut(layer_boxes(20000, 2 - layer, 100.0F, random), {}, cube);
    for (int level = 0; level < 3; ++level) EXPECT_EQ(cube.segments(level), 12U);
}

TEST(SampledCuts, ALayerOnTheFirstLevelGivesItsSegmentsToTheSecond) { check_layer_shape(0); }
TEST(SampledCuts, ALayerOnTheSecondLevelGivesItsSegmentsToTheFirst) { check_layer_shape(1); }

TEST(SampledCuts, DetectionsOfLayersAreExact) {
    std::mt19937_64 random(53);
    std::uniform_real_distribution<float> nudge(-0.05F, 0.05F);
    for (const int thin : {0, 1, 2}) {
        SCOPED_TRACE(testing::Message() << "thin axis " << thin);
        std::vector<Box<float, 3>> boxes = layer_boxes(6000, thin, 1.5F, random);
        PersistentCutPipeline<float, 3> pipeline;
        for (int step = 0; step < 6; ++step) {
            SCOPED_TRACE(step);
            if (step == 3) {
                const std::vector<Box<float, 3>> more = layer_boxes(3000, thin, 1.5F, random);
                boxes.insert(boxes.end(), more.begin(), more.end());
            }
            const std::vector<Pair> expected = test::brute_force_pairs<float, 3>(boxes);
            ASSERT_EQ(detected(pipeline, std::span<const Box<float, 3>>(boxes)), expected);
            for (Box<float, 3>& box : boxes) {
                for (int k = 0; k < 3; ++k) {
                    const float d = nudge(random);
                    box.min[k] += d;
                    box.max[k] += d;
                }
            }
        }
    }
}

/// First detections of lattices of every size from one box up, then the same pipeline on 40%
/// more boxes (a new number of segments: planes and order forgotten), against brute force.
template <class Input, int Dim>
void check_first_detections(std::uint64_t seed, std::size_t population) {
    std::mt19937_64 random(seed);
    DetectionSettings settings;
    settings.target_cell_population = population;
    using Real = float;
    constexpr bool kHeld = !std::is_same_v<Input, Real>;
    for (const std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{300}, std::size_t{4000}}) {
        SCOPED_TRACE(testing::Message() << "n " << n);
        const int side = static_cast<int>(std::ceil(std::pow(static_cast<double>(n), 1.0 / Dim))) + 2;
        std::vector<Box<Input, Dim>> boxes = lattice_boxes<Input, Dim>(n, side, side / 2 + 3, random);
        PersistentCutPipeline<Real, Dim, Input> pipeline;
        if constexpr (kHeld) {
            std::array<Input, Dim> origin{};
            for (int k = 0; k < Dim; ++k) origin[k] = static_cast<Input>(side) / 3;
            pipeline.set_origin(origin);
        }
        auto detect = [&](std::span<const Box<Input, Dim>> input) { return detected(pipeline, input, settings); };
        const std::vector<Pair> first = test::brute_force_pairs<Input, Dim>(boxes);
        ASSERT_EQ(detect(boxes), first);
        const std::vector<Box<Input, Dim>> more = lattice_boxes<Input, Dim>(n * 2 / 5 + 1, side, side / 2 + 3, random);
        boxes.insert(boxes.end(), more.begin(), more.end());
        const std::vector<Pair> expected = test::brute_force_pairs<Input, Dim>(boxes);
        ASSERT_EQ(detect(boxes), expected);
        ASSERT_EQ(detect(boxes), expected);
    }
}

TEST(SampledCuts, FirstDetectionsOfLatticesAreExact3D) { check_first_detections<float, 3>(41, 24); }
TEST(SampledCuts, FirstDetectionsOfLatticesAreExact2D) { check_first_detections<float, 2>(42, 24); }
TEST(SampledCuts, FirstDetectionsOfDoubleLatticesAreExact3D) { check_first_detections<double, 3>(43, 24); }
TEST(SampledCuts, FirstDetectionsOfDoubleLatticesAreExact2D) { check_first_detections<double, 2>(44, 24); }
// Few segments, so that the sample is a part of the boxes in 3D too.
TEST(SampledCuts, FirstDetectionsFromAPartialSampleAreExact3D) { check_first_detections<float, 3>(45, 1000); }

}  // namespace
}  // namespace smb::detail
