// SPDX-License-Identifier: MIT
// The worked example of the paper's Section 2.4 (Fig. 4, expressions (2)-(13)), step by step:
// each step is fed the paper's input list and must give the paper's output list. Vertex v's y
// partner is v ^ 1, so v >> 1 plays our level-0 item and v our corner. The whole pipeline on
// boxes drawn from these lists is test_paper_example_pipeline.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "paper/axial_cut.hpp"
#include "paper/cell_lists.hpp"
#include "paper/global_local_map.hpp"
#include "paper/mask_array.hpp"
#include "paper/shell_sort.hpp"
#include "paper/singular_regroup.hpp"
#include "paper_example_lists.hpp"

namespace smb::detail {
namespace {

using namespace paper_example;

/// Keys that make (8) the sorted order: a vertex's key is its rank in (8).
std::vector<double> keys_of_sorted_x12() {
    std::vector<double> key(kVertices);
    for (std::size_t rank = 0; rank < kX12Sorted.size(); ++rank) key[kX12Sorted[rank]] = static_cast<double>(rank);
    return key;
}

std::vector<AxisEntry<double>> entries(const std::vector<Item>& items, const std::vector<double>& key) {
    std::vector<AxisEntry<double>> list;
    for (const Item item : items) list.push_back({key[item], item});
    return list;
}

std::vector<Item> items(const std::vector<AxisEntry<double>>& list) {
    std::vector<Item> out;
    for (const auto& entry : list) out.push_back(entry.item);
    return out;
}

/// (4): the index array, slab of every Y1 pair (vertex v is in the slab of pair v >> 1).
std::vector<SegmentId> slab_of_pair() {
    std::vector<SegmentId> slab(kVertices / 2);
    for (std::size_t i = 0; i < kY1.size(); ++i) slab[kY1[i] >> 1] = i < 24 ? 0 : 1;
    return slab;
}

std::multiset<Item> as_set(const std::vector<Item>& list, std::size_t first, std::size_t last) {
    return {list.begin() + static_cast<std::ptrdiff_t>(first), list.begin() + static_cast<std::ptrdiff_t>(last)};
}

TEST(PaperExample, RegroupingMovesExactlyTheSingularItems) {
    const auto key = keys_of_sorted_x12();
    const auto previous = entries(kX12Previous, key);
    const std::vector<std::uint32_t> old_sections{0, 24, 48};
    const std::vector<std::uint32_t> new_sections{0, 24, 48};
    std::vector<AxisEntry<double>> regrouped = previous;
    RegroupScratch<double> scratch;
    regroup_by_parent_segment<double>(regrouped, old_sections, {}, slab_of_pair(), new_sections, scratch);
    const auto got = items(regrouped);
    EXPECT_EQ(as_set(got, 0, 24), as_set(kX12Regrouped, 0, 24));
    EXPECT_EQ(as_set(got, 24, 48), as_set(kX12Regrouped, 24, 48));
    EXPECT_EQ(scratch.singular.size(), 4U) << "singular items: 23, 22, 28, 29";
    // Normal items keep their order: removing the singular ones from ours and from (7) leaves
    // the same sequence.
    auto normal = [](std::vector<Item> list) {
        std::erase_if(list, [](Item v) { return v == 22 || v == 23 || v == 28 || v == 29; });
        return list;
    };
    EXPECT_EQ(normal(got), normal(kX12Regrouped));
}

TEST(PaperExample, DisThenCutGivesTheFourSubLists) {
    const auto key = keys_of_sorted_x12();
    auto x12 = entries(kX12Regrouped, key);
    for (std::size_t slab = 0; slab < 2; ++slab) {
        diminishing_increment_sort<double>(std::span(x12.data() + 24 * slab, 24), 2);
    }
    EXPECT_EQ(items(x12), kX12Sorted);

    std::vector<SegmentId> sub_list_of(kVertices);
    std::vector<std::uint32_t> begin;
    for (std::uint32_t slab = 0; slab < 2; ++slab) {
        cut_section<double>(std::span<const AxisEntry<double>>(x12.data() + 24 * slab, 24), 24 * slab, 2, 2 * slab,
                            sub_list_of, begin);
    }
    EXPECT_EQ(begin, (std::vector<std::uint32_t>{0, 12, 24, 36}));
    for (std::size_t v = 0; v < kVertices; ++v) EXPECT_EQ(sub_list_of[v] + 1, kSubListIndex[v]) << "vertex " << v;
}

TEST(PaperExample, Y1RegroupedByCellIsY2) {
    std::vector<SegmentId> sub_list_of(kVertices);
    for (std::size_t i = 0; i < kX12Sorted.size(); ++i) sub_list_of[kX12Sorted[i]] = static_cast<SegmentId>(i / 12);
    const std::vector<std::uint32_t> cell_begin{0, 12, 24, 36, 48};
    std::vector<Item> y2;
    std::vector<std::uint32_t> cursor;
    regroup_by_cell(kY1, 0, sub_list_of, cell_begin, y2, cursor);
    EXPECT_EQ(y2, kY2);
}

TEST(PaperExample, GlobalLocalMapOfSubList2) {
    GlobalLocalMap map;
    map.reset(12);
    for (std::size_t i = 12; i < 24; ++i) map.local(kX12Sorted[i] / 4);
    // (12): boxes 7, 10, 2, 0 get local numbers 0, 1, 2, 3.
    EXPECT_EQ(map.find(7), 0U);
    EXPECT_EQ(map.find(10), 1U);
    EXPECT_EQ(map.find(2), 2U);
    EXPECT_EQ(map.find(0), 3U);
    EXPECT_EQ(map.size(), 4U);
    map.clear_cell();
    EXPECT_EQ(map.find(7), GlobalLocalMap::kAbsent);
}

TEST(PaperExample, MaskArraySequence) {
    // Our bit 1 is the paper's X bit ("01"), our bit 0 its Y bit ("10").
    constexpr std::uint8_t kX = 2;
    constexpr std::uint8_t kY = 1;
    MaskArray mask;
    mask.reset(12);
    auto boxes_of_sub_list = [](std::size_t sub_list) {
        std::set<std::uint32_t> boxes;
        for (std::size_t i = 12 * sub_list; i < 12 * (sub_list + 1); ++i) boxes.insert(kX12Sorted[i] / 4);
        return boxes;
    };
    for (const auto box : boxes_of_sub_list(0)) mask.mark_cell_done(box, 1);
    // (13b)
    for (std::uint32_t box = 0; box < 12; ++box) {
        const bool in_first = box == 4 || box == 7 || box == 9 || box == 10;
        EXPECT_EQ(mask.bits(box), in_first ? kX : 0) << "box " << box;
    }
    EXPECT_TRUE(mask.already_checked(7, 10)) << "the pair shared by sub-lists 1 and 2 is skipped";
    for (const auto box : boxes_of_sub_list(1)) mask.mark_cell_done(box, 1);
    for (std::size_t sub_list = 0; sub_list < 2; ++sub_list) {
        for (const auto box : boxes_of_sub_list(sub_list)) mask.mark_segment_done(box, 0);
    }
    // (13c)
    for (std::uint32_t box = 0; box < 12; ++box) {
        const bool in_slab_one = box == 0 || box == 2 || box == 4 || box == 7 || box == 9 || box == 10;
        EXPECT_EQ(mask.bits(box), in_slab_one ? kY : 0) << "box " << box;
    }
    for (const auto box : boxes_of_sub_list(2)) mask.mark_cell_done(box, 1);
    // (13d)
    for (std::uint32_t box = 0; box < 12; ++box) {
        std::uint8_t expected = 0;
        if (box == 0 || box == 2 || box == 4 || box == 7 || box == 9 || box == 10) expected |= kY;
        if (box == 1 || box == 3 || box == 6 || box == 1) expected |= kX;
        if (boxes_of_sub_list(2).contains(box)) expected |= kX;
        EXPECT_EQ(mask.bits(box), expected) << "box " << box;
    }
}

}  // namespace
}  // namespace smb::detail
