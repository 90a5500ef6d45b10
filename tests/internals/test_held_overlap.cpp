// SPDX-License-Identifier: MIT
// The skin list's test of a pair of held boxes (src/skin/candidate_list.hpp): candidate_bits()'s
// hit bit, with and without the sure bit, against the closed overlap of smb/box.hpp, and its
// vacant bit, by which the pass over the candidates finds those to drop: never set for two boxes
// with min <= max (touching, flat, nested, far apart), always set where either box is
// empty_float_box(), whose pairs never hit.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/held_box.hpp"
#include "skin/candidate_list.hpp"
#include "smb/box.hpp"

namespace smb::detail {
namespace {

/// Boxes on a coarse lattice, so that many pairs touch on a face, an edge or a corner, and some
/// are flat; followed by one box of padding, as the skin list holds them (the lanes read past
/// the last box).
template <int Dim>
std::vector<Box<float, Dim>> lattice_boxes(std::size_t n, std::mt19937& random) {
    std::uniform_int_distribution<int> place(-6, 6);
    std::uniform_int_distribution<int> side(0, 4);
    std::vector<Box<float, Dim>> boxes(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
        for (int k = 0; k < Dim; ++k) {
            boxes[i].min[k] = static_cast<float>(place(random)) * 0.5F;
            boxes[i].max[k] = boxes[i].min[k] + static_cast<float>(side(random)) * 0.5F;
        }
    }
    return boxes;
}

template <int Dim>
void expect_bits_of_every_pair() {
    std::mt19937 random(11 + Dim);
    constexpr std::size_t n = 120;
    std::vector<Box<float, Dim>> boxes = lattice_boxes<Dim>(n, random);
    std::size_t overlapping = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < n; ++j) {
            const bool expected = overlaps(boxes[i], boxes[j]);
            overlapping += expected ? 1 : 0;
            const std::uint32_t bits = candidate_bits<Dim, false>(&boxes[i], &boxes[j], 0.0F);
            const std::uint32_t sure_bits = candidate_bits<Dim, true>(&boxes[i], &boxes[j], 0.0F);
            ASSERT_EQ(bits & kHitBit, expected ? kHitBit : 0U) << i << ' ' << j;
            ASSERT_EQ(sure_bits & kHitBit, expected ? kHitBit : 0U) << i << ' ' << j;
            ASSERT_EQ((bits | sure_bits) & kVacantBit, 0U) << i << ' ' << j;
        }
    }
    // Neither all nor none: the lattice makes both kinds (and the touching ones among them).
    EXPECT_GT(overlapping, n);
    EXPECT_LT(overlapping, n * n);

    // Each box in turn vacant, as the skin list leaves a fresh or gone box while its
    // candidates are tested: every pair with it is vacant and none hits.
    for (std::size_t v = 0; v < n; ++v) {
        const Box<float, Dim> kept = boxes[v];
        boxes[v] = empty_float_box<Dim>();
        for (std::size_t j = 0; j < n; ++j) {
            for (const auto& [a, b] : {std::pair{v, j}, std::pair{j, v}}) {
                ASSERT_EQ((candidate_bits<Dim, false>(&boxes[a], &boxes[b], 0.0F)), kVacantBit) << a << ' ' << b;
                ASSERT_EQ((candidate_bits<Dim, true>(&boxes[a], &boxes[b], 0.0F)), kVacantBit) << a << ' ' << b;
            }
        }
        boxes[v] = kept;
    }
}

TEST(HeldOverlap, BitsOfEveryPair2D) { expect_bits_of_every_pair<2>(); }
TEST(HeldOverlap, BitsOfEveryPair3D) { expect_bits_of_every_pair<3>(); }

}  // namespace
}  // namespace smb::detail
