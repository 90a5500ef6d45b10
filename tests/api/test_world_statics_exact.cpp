// SPDX-License-Identifier: MIT
// Static boxes against brute force where the moving boxes' cached copies of them are hardest to
// get right: faces within a float or a lattice step of a moving box's (quantized_bounds.hpp),
// statics of every size the grid puts on levels of its own (query/grid_index.hpp), and moving
// boxes creeping across static faces by steps far below their size.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <vector>

#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/filter.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

TEST(WorldFilters, StaticsTouchingWithinAFloatOfAMovingBoxPairExactly) {
    // The moving boxes test their cached statics as floats rounded outward and go to the exact
    // boxes only where the float test cannot tell: faces that meet, or miss by a double's ulp,
    // at coordinates no float holds, on every axis and both sides.
    World3d world;
    BoxId id = 0;
    std::vector<Pair> expected;
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 40; ++i) {
            const double x = 0.1 + 0.37 * i + 1e-9 * k;  // not a float
            for (const int side : {-1, 1}) {
                for (const int steps : {-2, -1, 0, 1, 2}) {
                    double face = x;  // the moving box's face, `steps` ulps from the static's
                    for (int s = 0; s < std::abs(steps); ++s) face = std::nextafter(face, steps > 0 ? 1e9 : -1e9);
                    Box3d fixed{{0, 0, 0}, {1, 1, 1}};
                    Box3d moving{{0, 0, 0}, {1, 1, 1}};
                    const double offset = 20.0 * static_cast<double>(id + 1);  // apart from the others on another axis
                    const int other = (k + 1) % 3;
                    fixed.min[other] = moving.min[other] = offset;
                    fixed.max[other] = moving.max[other] = offset + 1;
                    // side 1: the static below x, the moving box from `face` up; side -1 mirrored.
                    const bool meet = side > 0 ? steps <= 0 : steps >= 0;
                    if (side > 0) {
                        fixed.min[k] = x - 1;
                        fixed.max[k] = x;
                        moving.min[k] = face;
                        moving.max[k] = face + 1;
                    } else {
                        fixed.min[k] = x;
                        fixed.max[k] = x + 1;
                        moving.min[k] = face - 1;
                        moving.max[k] = face;
                    }
                    world.insert(id, fixed);
                    world.set_static(id, true);
                    world.insert(id + 1, moving);
                    if (meet) expected.push_back({id, id + 1});
                    id += 2;
                }
            }
        }
    }
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, expected);
}

/// Brute force over statics (every id below every moving id) and moving boxes: the pairs of a
/// static and a moving box and of two moving boxes, sorted.
template <std::floating_point Real, int Dim>
std::vector<Pair> static_and_moving_pairs(const std::map<BoxId, Box<Real, Dim>>& statics,
                                          const std::map<BoxId, Box<Real, Dim>>& moving) {
    std::vector<Pair> expected;
    for (const auto& [sid, s] : statics) {
        for (const auto& [mid, b] : moving) {
            if (overlaps(s, b)) expected.push_back({sid, mid});
        }
    }
    for (auto a = moving.begin(); a != moving.end(); ++a) {
        for (auto b = std::next(a); b != moving.end(); ++b) {
            if (overlaps(a->second, b->second)) expected.push_back({a->first, b->first});
        }
    }
    std::sort(expected.begin(), expected.end());
    return expected;
}

/// `steps` steps: `move(id, box)` may change each moving box and says whether it did; the World
/// is given the boxes that changed, and every detection is compared with brute force.
template <std::floating_point Real, int Dim, class Move>
void step_against_brute_force(World<Real, Dim>& world, const std::map<BoxId, Box<Real, Dim>>& statics,
                              std::map<BoxId, Box<Real, Dim>>& moving, int steps, Move move) {
    std::vector<Pair> pairs;
    for (int step = 0; step < steps; ++step) {
        std::vector<BoxId> ids;
        std::vector<Box<Real, Dim>> boxes;
        for (auto& [id, b] : moving) {
            if (!move(id, b)) continue;
            ids.push_back(id);
            boxes.push_back(b);
        }
        world.update(ids, boxes);
        world.detect(pairs);
        ASSERT_TRUE(same_pairs(pairs, static_and_moving_pairs(statics, moving))) << "step " << step;
    }
}

/// Statics whose faces lie within a few steps of a moving box's lattice (a 32767th of its fat
/// box's side, quantized_bounds.hpp) of the moving boxes' faces, on every axis and both sides,
/// and moving boxes that creep across them by a fraction of a step at each detection, inside
/// their fat boxes: every detection against brute force.
template <std::floating_point Real, int Dim>
void check_statics_within_a_lattice_step() {
    using B = Box<Real, Dim>;
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    const Real step = static_cast<Real>(2.0 / 32767);  // the lattice step of a fat box of side 2
    BoxId id = 0;
    for (int k = 0; k < Dim; ++k) {
        for (const int side : {-1, 1}) {
            for (const double steps : {-3.0, -1.0, -0.5, 0.0, 0.5, 1.0, 3.0}) {
                for (const int ulps : {-1, 0, 1}) {
                    B s;
                    for (int j = 0; j < Dim; ++j) {
                        s.min[j] = 0;
                        s.max[j] = 1;
                    }
                    Real face = static_cast<Real>(side < 0 ? 0.0 : 1.0) + static_cast<Real>(steps) * step;
                    for (int u = 0; u < std::abs(ulps); ++u) face = std::nextafter(face, static_cast<Real>(10 * ulps));
                    // side -1: the static ends at `face` near the moving boxes' low faces; +1 mirrored.
                    s.min[k] = side < 0 ? face - 1 : face;
                    s.max[k] = side < 0 ? face : face + 1;
                    statics[id] = s;
                    world.insert(id, s);
                    world.set_static(id, true);
                    ++id;
                }
            }
        }
    }
    for (int m = 0; m < 3; ++m) {
        B b;
        for (int j = 0; j < Dim; ++j) {
            b.min[j] = 0;
            b.max[j] = 1;
        }
        moving[1000 + m] = b;
        world.insert(1000 + m, b);
    }
    std::vector<Pair> pairs;
    for (int t = 0; t < 40; ++t) {
        // Each moving box creeps by its own fraction of a step along its own direction.
        for (auto& [mid, b] : moving) {
            const auto m = static_cast<int>(mid - 1000);
            for (int j = 0; j < Dim; ++j) {
                const Real by =
                    static_cast<Real>((j + m) % 2 == 0 ? 1 : -1) * step * static_cast<Real>(0.13 + 0.11 * m);
                b.min[j] = static_cast<Real>(-3) * step + by * static_cast<Real>(t) + (m == 2 ? step : Real(0));
                b.max[j] = 1 + static_cast<Real>(3) * step - by * static_cast<Real>(t) * static_cast<Real>(m);
            }
            world.update(mid, b);
        }
        world.detect(pairs);
        const std::vector<Pair> expected = static_and_moving_pairs(statics, moving);
        ASSERT_TRUE(same_pairs(pairs, expected)) << "detection " << t;
    }
}

TEST(WorldFilters, StaticsWithinALatticeStepOfMovingBoxesPairExactly) {
    check_statics_within_a_lattice_step<double, 3>();
    check_statics_within_a_lattice_step<float, 3>();
    check_statics_within_a_lattice_step<double, 2>();
    check_statics_within_a_lattice_step<float, 2>();
}

/// Statics of every size the grid puts on levels of its own (query/grid_index.hpp): small ones on
/// the finest (points among them), wider ones on coarser levels, and floors on the coarsest;
/// moving boxes of mixed sizes that wander, jump and stop among them; against brute force.
template <std::floating_point Real, int Dim>
void check_statics_of_mixed_sizes(std::uint64_t seed) {
    using B = Box<Real, Dim>;
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Random random(seed);
    const double space = Dim == 3 ? 30 : 120;
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    std::vector<BoxId> static_ids;
    for (BoxId id = 0; id < 600; ++id) {
        const double kind = uniform(random, 0, 1);
        B b = kind < 0.1    ? random_box<Real, Dim>(random, 0, space, 0, 0)      // points
              : kind < 0.8  ? random_box<Real, Dim>(random, 0, space, 0.5, 1.5)  // small
              : kind < 0.98 ? random_box<Real, Dim>(random, 0, space, 3, 8)      // wider
                            : random_box<Real, Dim>(random, 0, space, 0.5, 1.5);
        if (kind >= 0.98) {  // a floor across the whole space on every axis but one
            for (int k = 1; k < Dim; ++k) {
                b.min[k] = static_cast<Real>(-10);
                b.max[k] = static_cast<Real>(space + 10);
            }
        }
        statics[id] = b;
        world.insert(id, b);
        static_ids.push_back(id);
    }
    world.set_static(static_ids, true);
    for (BoxId id = 1000; id < 1150; ++id) {
        moving[id] = random_box<Real, Dim>(random, 0, space, 0.2, 3);
        world.insert(id, moving[id]);
    }
    step_against_brute_force(world, statics, moving, 20, [&](BoxId, B& b) {
        if (chance(random, 0.2)) return false;  // stays where it is
        b = chance(random, 0.02) ? random_box<Real, Dim>(random, 0, space, 0.2, 3) : perturbed(random, b, 0.3, 0.05);
        return true;
    });
}

TEST(WorldFilters, StaticsOfMixedSizesMatchBruteForce) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        check_statics_of_mixed_sizes<double, 3>(seed);
        check_statics_of_mixed_sizes<float, 3>(seed);
        check_statics_of_mixed_sizes<double, 2>(seed);
        check_statics_of_mixed_sizes<float, 2>(seed);
    }
}

/// Moving boxes that creep among the statics by steps far below their size (1/1024 on an axis
/// a step, on a binary grid, so that faces land on the statics' faces exactly), now and then
/// turning back: any answer a step reuses after the box moved past a face shows as a pair
/// missed or too many, against brute force at every step.
template <std::floating_point Real, int Dim>
void check_boxes_creeping_across_static_faces(std::uint64_t seed) {
    using B = Box<Real, Dim>;
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    Random random(seed);
    World<Real, Dim> world;
    std::map<BoxId, B> statics;
    std::map<BoxId, B> moving;
    std::vector<BoxId> static_ids;
    const int per_axis = Dim == 3 ? 5 : 10;
    const int cells = Dim == 3 ? per_axis * per_axis * per_axis : per_axis * per_axis;
    for (BoxId id = 0; id < static_cast<BoxId>(cells); ++id) {  // unit boxes 0.5 apart
        B b;
        auto rest = static_cast<int>(id);
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = static_cast<Real>(1.5 * (rest % per_axis));
            b.max[k] = b.min[k] + 1;
            rest /= per_axis;
        }
        statics[id] = b;
        world.insert(id, b);
        static_ids.push_back(id);
    }
    world.set_static(static_ids, true);
    constexpr double kStep = 1.0 / 1024;
    std::map<BoxId, std::array<int, Dim>> pace;  // steps of kStep a detection, on each axis
    for (BoxId id = 1000; id < 1040; ++id) {
        B b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = static_cast<Real>(kStep * static_cast<double>(uniform_index(random, 1536 * per_axis)));
            b.max[k] = b.min[k] + static_cast<Real>(static_cast<double>(1 + uniform_index(random, 64)) / 64);
            pace[id][k] = static_cast<int>(uniform_index(random, 7)) - 3;
        }
        moving[id] = b;
        world.insert(id, b);
    }
    step_against_brute_force(world, statics, moving, 300, [&](BoxId id, B& b) {
        for (int k = 0; k < Dim; ++k) {
            if (chance(random, 0.03)) pace[id][k] = -pace[id][k];
            const auto by = static_cast<Real>(kStep * pace[id][k]);
            b.min[k] += by;
            b.max[k] += by;
        }
        return true;
    });
}

TEST(WorldFilters, BoxesCreepingAcrossStaticFacesMatchBruteForce) {
    for (const std::uint64_t seed : {1u, 2u}) {
        check_boxes_creeping_across_static_faces<double, 3>(seed);
        check_boxes_creeping_across_static_faces<float, 3>(seed);
        check_boxes_creeping_across_static_faces<double, 2>(seed);
        check_boxes_creeping_across_static_faces<float, 2>(seed);
    }
}
}  // namespace
}  // namespace smb::test
