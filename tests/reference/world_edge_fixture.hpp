// SPDX-License-Identifier: MIT
#pragma once
// The fixture of the World edge-case suites (test_world_edge_cases.cpp, test_world_life_cycle.cpp):
// a World and the brute-force reference driven by the same calls, and a detection checked
// against it.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/reference_world.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {

template <typename WorldType>
class WorldEdgeCaseTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;
    using Point = std::array<double, Dim>;

    /// The box [lo, hi] on every axis.
    static BoxT cube(double lo, double hi) {
        BoxT box;
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = static_cast<Real>(lo);
            box.max[k] = static_cast<Real>(hi);
        }
        return box;
    }

    static BoxT from_corners(const Point& lo, const Point& hi) {
        BoxT box;
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = static_cast<Real>(lo[k]);
            box.max[k] = static_cast<Real>(hi[k]);
        }
        return box;
    }

    void insert(BoxId id, const BoxT& box) {
        world_.insert(id, box);
        reference_.insert(id, box);
    }
    void update(BoxId id, const BoxT& box) {
        world_.update(id, box);
        reference_.update(id, box);
    }
    void remove(BoxId id) {
        world_.remove(id);
        reference_.remove(id);
    }
    void insert_all(const std::vector<BoxId>& ids, const std::vector<BoxT>& boxes) {
        world_.insert(ids, boxes);
        for (std::size_t i = 0; i < ids.size(); ++i) reference_.insert(ids[i], boxes[i]);
    }
    void assign(const std::vector<BoxT>& boxes) {
        world_.assign(boxes);
        reference_.assign(boxes);
    }

    /// Detects and checks against brute force; returns the pairs as reported.
    std::vector<Pair> check(const char* what) {
        SCOPED_TRACE(what);
        EXPECT_TRUE(same_contents(world_, reference_));
        std::vector<Pair> pairs;
        const DetectStats stats = world_.detect(pairs);
        EXPECT_TRUE(same_pairs(pairs, reference_.pairs(), reference_.describer()));
        EXPECT_EQ(stats.pairs, pairs.size());
        EXPECT_EQ(stats.boxes, reference_.size());
        return pairs;
    }

    /// Every box moved by `shift` along every axis, in one batch update.
    void shift_all(double shift) {
        std::vector<BoxId> ids = reference_.ids();
        std::vector<BoxT> boxes;
        for (const BoxId id : ids) {
            BoxT box = reference_.box(id);
            for (int k = 0; k < Dim; ++k) {
                box.min[k] = static_cast<Real>(box.min[k] + shift);
                box.max[k] = static_cast<Real>(box.max[k] + shift);
            }
            boxes.push_back(box);
        }
        world_.update(ids, boxes);
        for (std::size_t i = 0; i < ids.size(); ++i) reference_.update(ids[i], boxes[i]);
    }

    World<Real, Dim> world_{test_settings()};
    ReferenceWorld<Real, Dim> reference_;
};

}  // namespace smb::test
