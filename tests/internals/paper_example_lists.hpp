// SPDX-License-Identifier: MIT
#pragma once
// The lists of the paper's worked example (Section 2.4, Fig. 4): twelve 2D boxes, vertices
// 4n..4n+3 of box n. Vertices 4n and 4n+1 are the box's upper corners, 4n+2 and 4n+3 its lower
// ones; 4n and 4n+3 its left corners, 4n+1 and 4n+2 its right ones (as the lists order them).

#include <cstddef>
#include <vector>

#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"

namespace smb::detail::paper_example {

// (2): Y1 sorted and cut into slabs I and II of 24 vertices.
const std::vector<Item> kY1 = {18, 19, 10, 11, 16, 17, 2,  3,  8,  9,  0,  1,  42, 43, 38, 39,
                               30, 31, 40, 41, 36, 37, 28, 29, 22, 23, 34, 35, 32, 33, 14, 15,
                               20, 21, 12, 13, 6,  7,  46, 47, 26, 27, 4,  5,  24, 25, 44, 45};
// (3): X12 as the previous step left it.
const std::vector<Item> kX12Previous = {36, 39, 16, 19, 37, 38, 17, 18, 31, 40, 43, 30, 23, 8,  11, 41,
                                        42, 0,  3,  22, 9,  10, 1,  2,  4,  7,  24, 27, 12, 15, 5,  6,
                                        13, 14, 25, 26, 28, 20, 29, 32, 35, 44, 47, 21, 45, 46, 33, 34};
// (7): X12 after the singular items 23, 22 (to slab II) and 28, 29 (to slab I) moved.
const std::vector<Item> kX12Regrouped = {36, 39, 16, 19, 37, 38, 17, 18, 31, 40, 43, 30, 28, 8,  11, 41,
                                         42, 0,  3,  29, 9,  10, 1,  2,  4,  7,  24, 27, 12, 15, 5,  6,
                                         13, 14, 25, 26, 23, 20, 22, 32, 35, 44, 47, 21, 45, 46, 33, 34};
// (8) = (9): each slab of X12 sorted by DIS, then cut into sub-lists 1-4 of 12.
const std::vector<Item> kX12Sorted = {36, 39, 37, 38, 16, 19, 17, 18, 28, 31, 40, 43, 29, 30, 41, 42,
                                      8,  11, 0,  3,  9,  10, 1,  2,  4,  7,  24, 27, 5,  6,  12, 15,
                                      13, 14, 25, 26, 20, 23, 32, 35, 44, 47, 21, 22, 45, 46, 33, 34};
// (10): Y2, Y1 regrouped by sub-list.
const std::vector<Item> kY2 = {18, 19, 16, 17, 43, 38, 39, 31, 40, 36, 37, 28, 10, 11, 2,  3,
                               8,  9,  0,  1,  42, 30, 41, 29, 14, 15, 12, 13, 6,  7,  26, 27,
                               4,  5,  24, 25, 22, 23, 34, 35, 32, 33, 20, 21, 46, 47, 44, 45};

// (11): the index array of sub-lists, numbered from 1 in the paper.
const std::vector<SegmentId> kSubListIndex = {2, 2, 2, 2, 3, 3, 3, 3, 2, 2, 2, 2, 3, 3, 3, 3, 1, 1, 1, 1, 4, 4, 4, 4,
                                              3, 3, 3, 3, 1, 2, 2, 1, 4, 4, 4, 4, 1, 1, 1, 1, 1, 2, 2, 1, 4, 4, 4, 4};

constexpr std::size_t kVertices = 48;

}  // namespace smb::detail::paper_example
