// SPDX-License-Identifier: MIT
// The boxes copied grouped by column while they jump across cells (src/cuts/column_presort.hpp;
// the copy itself: test_sampled_cuts.cpp): started by hints that miss, stopped once most boxes
// keep their columns; and the persistent cuts exact with it on, step after step of boxes that
// jump anywhere, against brute force.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "cuts/column_presort.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "internals/pipeline_pairs.hpp"
#include "reference/brute_force.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {
namespace {

template <int Dim>
std::vector<Box<float, Dim>> scattered_boxes(std::size_t n, float side, std::mt19937_64& random) {
    std::uniform_real_distribution<float> place(0.0F, side);
    std::uniform_real_distribution<float> extent(0.2F, 1.0F);
    std::vector<Box<float, Dim>> boxes(n);
    for (Box<float, Dim>& box : boxes) {
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = place(random);
            box.max[k] = box.min[k] + extent(random);
        }
    }
    return boxes;
}

/// Planes of every group of every level but the deepest, cut at the boxes' lower corners.
template <int Dim>
CutTree<float, Dim> planes_for(std::span<const Box<float, Dim>> boxes, std::uint32_t segments) {
    CutTree<float, Dim> cuts;
    cuts.reshape(segments);
    // Evenly spaced planes over [0, 100): where they lie does not matter to the sort.
    for (int level = 0; level + 1 < Dim; ++level) {
        for (std::size_t group = 0; group < cuts.groups(level); ++group) {
            QuantileSelector<float> selector;
            for (std::size_t i = 0; i < 4 * segments; ++i)
                selector.keys.push_back(100.0F * static_cast<float>(i) / static_cast<float>(4 * segments));
            cuts.cut(level, group, selector);
        }
    }
    (void)boxes;
    return cuts;
}

TEST(ColumnPresort, StartsWhenHintsMissAndStopsWhenBoxesKeepTheirColumns) {
    std::mt19937_64 random(12);
    std::vector<Box<float, 2>> boxes = scattered_boxes<2>(4000, 100.0F, random);
    const CutTree<float, 2> cuts = planes_for<2>(boxes, 16);
    ColumnPresort<float, 2, float> presort;
    presort.judge(0.02);  // below tuning::column_copy_start_misses
    EXPECT_FALSE(presort.sorting());
    presort.judge(0.6);
    EXPECT_TRUE(presort.sorting());
    presort.note_columns(boxes, {}, cuts);  // nothing to compare with yet
    EXPECT_TRUE(presort.sorting());
    boxes = scattered_boxes<2>(4000, 100.0F, random);  // every box jumps anywhere
    presort.note_columns(boxes, {}, cuts);
    EXPECT_TRUE(presort.sorting());
    EXPECT_GE(presort.bytes_held(), 4000 / 16 * sizeof(std::uint32_t));
    // A few boxes that jump (under half) still leave the order to last step's cells.
    for (std::size_t i = 0; i < boxes.size(); i += 3) boxes[i] = scattered_boxes<2>(1, 100.0F, random)[0];
    presort.note_columns(boxes, {}, cuts);
    EXPECT_FALSE(presort.sorting());
    EXPECT_EQ(presort.bytes_held(), 0U);
}

template <int Dim>
void check_jumping_boxes(std::uint64_t seed) {
    std::mt19937_64 random(seed);
    const std::size_t n = 3000;
    const float side = Dim == 3 ? 22.0F : 90.0F;
    std::vector<Box<float, Dim>> boxes = scattered_boxes<Dim>(n, side, random);
    PersistentCutPipeline<float, Dim> pipeline;
    std::uniform_real_distribution<float> jump(-0.5F * side, 0.5F * side);
    std::uniform_real_distribution<float> unit(0.0F, 1.0F);
    bool presorted = false;
    for (int step = 0; step < 30; ++step) {
        SCOPED_TRACE(step);
        if (step == 20) {
            // The boxes settle: the sort must step aside again.
            const std::vector<Pair> expected = test::brute_force_pairs<float, Dim>(boxes);
            for (int k = 0; k < 3; ++k)
                ASSERT_EQ(detected(pipeline, std::span<const Box<float, Dim>>(boxes)), expected);
            EXPECT_FALSE(pipeline.presorting());
        }
        for (Box<float, Dim>& box : boxes) {
            for (int k = 0; k < Dim; ++k) {
                const float d = jump(random);
                box.min[k] += d;
                box.max[k] += d;
            }
        }
        // A box that shrinks to a point, so that the columns see every shape.
        Box<float, Dim>& point = boxes[static_cast<std::size_t>(unit(random) * (n - 1))];
        point.max = point.min;
        const std::vector<Pair> expected = test::brute_force_pairs<float, Dim>(boxes);
        ASSERT_EQ(detected(pipeline, std::span<const Box<float, Dim>>(boxes)), expected);
        presorted = presorted || pipeline.presorting();
    }
    EXPECT_TRUE(presorted) << "the boxes jumped across columns at every step";
}

TEST(ColumnPresort, PersistentCutsStayExactWhileTheOrderIsSortedByColumn3D) { check_jumping_boxes<3>(21); }
TEST(ColumnPresort, PersistentCutsStayExactWhileTheOrderIsSortedByColumn2D) { check_jumping_boxes<2>(22); }

}  // namespace
}  // namespace smb::detail
