// SPDX-License-Identifier: MIT
// World::bytes_held() of Pipeline::paper_lists per box stays near the paper's count (7 lists of
// 8N 4-byte integers in 3D, 5 of 4N in 2D) plus the boxes, at a slow and a fast update factor.
// The bounds hold what docs/reproduction.md measures at 100k boxes (354 and 164 B/box at
// Λ = 1e-5) with some room; a pipeline that kept a spare list or doubled its lists would exceed
// them.

#include <gtest/gtest.h>

#include <cstddef>
#include <random>
#include <vector>

#include "smb/world.hpp"

namespace {

template <int Dim>
double bytes_per_box_after_steps(double update_factor) {
    constexpr std::size_t kBoxes = 50000;
    const double side = 60.0;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<smb::BoxId> ids(kBoxes);
    std::vector<smb::Box<double, Dim>> boxes(kBoxes);
    for (std::size_t i = 0; i < kBoxes; ++i) {
        ids[i] = i;
        for (int k = 0; k < Dim; ++k) {
            boxes[i].min[k] = unit(rng) * (side - 1.0);
            boxes[i].max[k] = boxes[i].min[k] + 0.4 + 0.6 * unit(rng);
        }
    }
    smb::WorldSettings settings;
    settings.pipeline = smb::Pipeline::paper_lists;
    smb::World<double, Dim> world(settings);
    world.insert(ids, boxes);
    std::vector<smb::Pair> pairs;
    for (int step = 0; step < 4; ++step) {
        world.detect(pairs);
        for (auto& box : boxes) {
            for (int k = 0; k < Dim; ++k) {
                const double shift = (2.0 * unit(rng) - 1.0) * update_factor * side;
                box.min[k] += shift;
                box.max[k] += shift;
            }
        }
        world.update(ids, boxes);
    }
    world.detect(pairs);
    return static_cast<double>(world.bytes_held()) / kBoxes;
}

TEST(PaperMemory, ThreeDimensionsPerBox) {
    EXPECT_LT(bytes_per_box_after_steps<3>(1e-5), 400.0);
    EXPECT_LT(bytes_per_box_after_steps<3>(1e-3), 400.0);
}

TEST(PaperMemory, TwoDimensionsPerBox) {
    EXPECT_LT(bytes_per_box_after_steps<2>(1e-5), 200.0);
    EXPECT_LT(bytes_per_box_after_steps<2>(1e-3), 200.0);
}

}  // namespace
