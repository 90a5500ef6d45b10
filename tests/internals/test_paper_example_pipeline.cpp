// SPDX-License-Identifier: MIT
// The worked example of the paper's Section 2.4 end to end: twelve boxes whose coordinates give
// the paper's sorted lists (2) and (8), run through PaperPipeline for two steps, the lists it
// keeps held against the paper's after every step, then the cells checked with its flag matrix
// and mask, and a World with Pipeline::paper_lists giving the same pairs.
//
// Where the pipeline and the paper differ, the test asserts the pipeline's version and says why:
//  - Corners of one box that share a coordinate tie; the paper lists them by vertex number, the
//    pipeline by its own corner number (lower y end first), so tied runs are compared as sets.
//  - The pipeline's Y1 holds one item per y value (the paper's even vertex; the odd one follows
//    it, as the paper's step 1 says), so the paper's Y1 is compared pair by pair.
//  - (3), X12 as the step before left it, is no sorted order of any coordinates (its slab I puts
//    box 7's right end before box 5's left end, its slab II after), so the step before is held
//    to (3) by the items of each slab, and the regrouped list (7) by its singular items: the
//    pipeline merges them into their sorted place rather than into the holes they left.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "core/box_store.hpp"
#include "paper/cell_check.hpp"
#include "paper/paper_pipeline.hpp"
#include "paper_example_lists.hpp"
#include "reference/brute_force.hpp"
#include "smb/world.hpp"

namespace smb::detail {
namespace {

using namespace paper_example;
using Pipeline2 = PaperPipeline<double, 2>;

/// The boxes of the paper's Fig. 4 (the step of expressions (2) and (8)): each coordinate is the
/// rank of its value in a total order consistent with the paper's lists.
const std::vector<Box2d> kBoxes = {
    {{17, 3}, {19, 5}},   {{0, 18}, {2, 21}},   {{16, 1}, {18, 4}}, {{3, 15}, {4, 17}},
    {{8, 0}, {9, 2}},     {{13, 12}, {21, 16}}, {{1, 20}, {5, 22}}, {{10, 8}, {12, 11}},
    {{14, 13}, {23, 14}}, {{6, 7}, {7, 10}},    {{11, 6}, {15, 9}}, {{20, 19}, {22, 23}},
};

/// The step before: box 7's top lies above box 5's bottom, so the paper's singular items
/// 28, 29 (box 7's top) are in slab II and 22, 23 (box 5's bottom) in slab I.
std::vector<Box2d> boxes_of_step_before() {
    auto boxes = kBoxes;
    boxes[7].max[1] = 12.5;
    return boxes;
}

/// The paper's number of our corner (slot << 2 | y end << 1 | x end).
Item paper_vertex(Item corner) {
    const Item box = corner >> 2;
    const bool upper = ((corner >> 1) & 1U) != 0;
    const bool right = (corner & 1U) != 0;
    const Item offset = upper ? (right ? 1 : 0) : (right ? 2 : 3);
    return 4 * box + offset;
}

/// Our level-0 list as the paper's Y1: each y value's two vertices, even one first.
std::vector<Item> paper_y1(const Pipeline2& pipeline) {
    std::vector<Item> y1;
    for (const auto& entry : pipeline.level(0).list) {
        const Item box = entry.item >> 1;
        const Item even = (entry.item & 1U) != 0 ? 4 * box : 4 * box + 2;
        y1.push_back(even);
        y1.push_back(even + 1);
    }
    return y1;
}

/// `vertices` with every run of tied vertices (same `tie_key`) put in vertex order.
template <class TieKey>
std::vector<Item> ties_in_vertex_order(std::vector<Item> vertices, TieKey tie_key) {
    std::size_t first = 0;
    for (std::size_t i = 1; i <= vertices.size(); ++i) {
        if (i == vertices.size() || tie_key(vertices[i]) != tie_key(vertices[first])) {
            std::sort(vertices.begin() + static_cast<std::ptrdiff_t>(first),
                      vertices.begin() + static_cast<std::ptrdiff_t>(i));
            first = i;
        }
    }
    return vertices;
}

// A vertex's x value is its box's and its left/right end; its y value its box's and upper/lower.
Item x_tie(Item vertex) { return (vertex / 4) * 2 + ((vertex % 4 == 1 || vertex % 4 == 2) ? 1 : 0); }
Item y_tie(Item vertex) { return vertex / 2; }

std::vector<Item> paper_x12(const Pipeline2& pipeline) {
    std::vector<Item> x12;
    for (const auto& entry : pipeline.level(1).list) x12.push_back(paper_vertex(entry.item));
    return ties_in_vertex_order(x12, x_tie);
}

std::multiset<Item> slab(const std::vector<Item>& list, std::size_t which) {
    return {list.begin() + static_cast<std::ptrdiff_t>(24 * which),
            list.begin() + static_cast<std::ptrdiff_t>(24 * (which + 1))};
}

std::vector<Pair> sorted_pairs(std::vector<Pair> pairs) {
    for (auto& pair : pairs) {
        if (pair.b < pair.a) std::swap(pair.a, pair.b);
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

class PaperExamplePipeline : public ::testing::Test {
protected:
    PaperExamplePipeline() {
        for (BoxId id = 0; id < 12; ++id) ids_.push_back(id);
    }

    std::vector<Pair> detect() {
        std::vector<Pair> pairs;
        auto report = [&](Slot a, Slot b) { pairs.push_back({a, b}); };
        DetectProfile profile;
        pipeline_.detect(store_.boxes(), report, true, profile);
        return sorted_pairs(pairs);
    }

    void run_both_steps() {
        const auto before = boxes_of_step_before();
        store_.insert(ids_, before);
        detect();
        store_.update(ids_, kBoxes);
    }

    /// 12 boxes: two slabs, two sub-lists in each.
    static WorldSettings example_settings() {
        WorldSettings settings;
        settings.target_cell_population = 3;
        return settings;
    }

    WorldSettings settings_ = example_settings();
    BoxStore<double, 2> store_;
    Pipeline2 pipeline_{settings_};
    std::vector<BoxId> ids_;
};

TEST_F(PaperExamplePipeline, StepBeforeHoldsTheSlabsOfExpression3) {
    store_.insert(ids_, boxes_of_step_before());
    detect();
    ASSERT_EQ(pipeline_.cuts(), 2U);
    EXPECT_EQ(pipeline_.level(0).segment_begin, (std::vector<std::uint32_t>{0, 12, 24}));
    const auto x12 = paper_x12(pipeline_);
    EXPECT_EQ(slab(x12, 0), slab(kX12Previous, 0));
    EXPECT_EQ(slab(x12, 1), slab(kX12Previous, 1));
}

TEST_F(PaperExamplePipeline, ListsAfterEveryStepAreThePapers) {
    run_both_steps();
    const auto pairs = detect();
    // (2) and its cut into slabs I and II.
    EXPECT_EQ(paper_y1(pipeline_), kY1);
    EXPECT_EQ(pipeline_.level(0).segment_begin, (std::vector<std::uint32_t>{0, 12, 24}));
    // (7): the regrouping moved the singular items 22, 23 to slab II and 28, 29 to slab I.
    EXPECT_EQ(pipeline_.level(1).section_begin, (std::vector<std::uint32_t>{0, 24, 48}));
    EXPECT_EQ(slab(paper_x12(pipeline_), 0), slab(kX12Regrouped, 0));
    EXPECT_EQ(slab(paper_x12(pipeline_), 1), slab(kX12Regrouped, 1));
    // (8) = (9): each slab sorted, cut into sub-lists 1-4 of 12; (11) the index array.
    EXPECT_EQ(paper_x12(pipeline_), kX12Sorted);
    EXPECT_EQ(pipeline_.level(1).segment_begin, (std::vector<std::uint32_t>{0, 12, 24, 36, 48}));
    for (Item corner = 0; corner < kVertices; ++corner) {
        EXPECT_EQ(pipeline_.cell_of()[corner] + 1, kSubListIndex[paper_vertex(corner)]) << corner;
    }
    // (10): Y2, Y1 regrouped by sub-list.
    std::vector<Item> y2;
    for (const Item corner : pipeline_.cell_list(0)) y2.push_back(paper_vertex(corner));
    EXPECT_EQ(ties_in_vertex_order(y2, y_tie), kY2);
    EXPECT_EQ(std::count(pipeline_.oversized().begin(), pipeline_.oversized().end(), 1), 0);
    EXPECT_EQ(pairs, sorted_pairs(test::brute_force_pairs<double, 2>(kBoxes)));
    EXPECT_TRUE(std::find(pairs.begin(), pairs.end(), Pair{7, 10}) != pairs.end());
}

TEST_F(PaperExamplePipeline, FlagMatrixFindsSevenTenAndTheMaskSkipsItOnce) {
    run_both_steps();
    detect();
    // The check of Section 2.4, cell by cell, on the pipeline's own lists.
    CellChecker<double, 2> checker;
    GlobalLocalMap map;
    MaskArray mask;
    map.reset(12);
    mask.reset(12);
    const auto& x12 = pipeline_.level(1);
    std::vector<std::vector<Pair>> reported(4);
    for (std::size_t cell = 0; cell < 4; ++cell) {
        const std::uint32_t first = x12.segment_begin[cell];
        typename CellChecker<double, 2>::CellLists lists;
        lists.upper[0] = pipeline_.cell_list(0).subspan(first, 12);
        lists.deepest = std::span<const AxisEntry<double>>(x12.list.data() + first, 12);
        checker.check(lists, pipeline_.oversized(), store_.boxes(), map, mask, [&](Slot a, Slot b) {
            reported[cell].push_back({a, b});
        });
        if (cell < 2) {
            // The flag matrix of sub-lists 1 and 2 holds both axes' bits for (7, 10).
            const std::uint32_t a = std::min(map.find(7), map.find(10));
            const std::uint32_t b = std::max(map.find(7), map.find(10));
            EXPECT_EQ(checker.flag_matrix()[a * map.size() + b], 3U) << "sub-list " << cell + 1;
        }
        if (cell == 1) {
            // (12): the global-local map of sub-list 2.
            EXPECT_EQ(map.boxes(), (std::vector<std::uint32_t>{7, 10, 2, 0}));
        }
        for (const std::uint32_t box : map.boxes()) mask.mark_cell_done(box, 1);
        map.clear_cell();
        if (cell == 0) {
            // (13b): the boxes of sub-list 1 carry the x bit.
            for (std::uint32_t box = 0; box < 12; ++box) {
                const bool in_first = box == 4 || box == 7 || box == 9 || box == 10;
                EXPECT_EQ(mask.bits(box), in_first ? 2 : 0) << "box " << box;
            }
        }
        if (cell % 2 == 1) {
            for (std::uint32_t i = x12.segment_begin[cell - 1]; i < x12.segment_begin[cell + 1]; ++i) {
                mask.mark_segment_done(x12.list[i].item >> 2, 0);
            }
        }
        if (cell == 1) {
            // (13c): slab I done, its boxes carry the y bit alone.
            for (std::uint32_t box = 0; box < 12; ++box) {
                const bool in_slab_one = box == 0 || box == 2 || box == 4 || box == 7 || box == 9 || box == 10;
                EXPECT_EQ(mask.bits(box), in_slab_one ? 1 : 0) << "box " << box;
            }
        }
    }
    EXPECT_EQ(sorted_pairs(reported[0]), (std::vector<Pair>{{7, 10}})) << "found in sub-list 1";
    EXPECT_EQ(sorted_pairs(reported[1]), (std::vector<Pair>{{0, 2}})) << "(7, 10) skipped in sub-list 2";
    std::vector<Pair> all;
    for (const auto& cell : reported) all.insert(all.end(), cell.begin(), cell.end());
    EXPECT_EQ(sorted_pairs(all), sorted_pairs(test::brute_force_pairs<double, 2>(kBoxes)));
}

TEST(PaperExampleWorld, PaperListsGiveTheSamePairs) {
    WorldSettings settings;
    settings.pipeline = Pipeline::paper_lists;
    settings.target_cell_population = 3;
    World2d world(settings);
    std::vector<BoxId> ids;
    for (BoxId id = 0; id < 12; ++id) ids.push_back(id);
    const auto before = boxes_of_step_before();
    world.insert(ids, before);
    std::vector<Pair> pairs;
    world.detect(pairs);
    EXPECT_EQ(sorted_pairs(pairs), sorted_pairs(test::brute_force_pairs<double, 2>(before)));
    world.update(ids, kBoxes);
    world.detect(pairs);
    EXPECT_EQ(sorted_pairs(pairs), (std::vector<Pair>{{0, 2}, {1, 6}, {5, 8}, {7, 10}}));
}

}  // namespace
}  // namespace smb::detail
