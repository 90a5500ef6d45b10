// SPDX-License-Identifier: MIT
// Scenes that are easy to get wrong: empty and single-box worlds, identical, touching and
// degenerate boxes, coplanar and collinear scenes, extreme sizes and coordinates, a floor
// under a pile of grains. Every world is driven incrementally and checked against brute force
// after each detection; the life cycle calls are in test_world_life_cycle.cpp.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/world_edge_fixture.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

TYPED_TEST_SUITE(WorldEdgeCaseTest, WorldTypes, WorldTypeNames);

TYPED_TEST(WorldEdgeCaseTest, EmptyWorld) {
    std::vector<Pair> pairs{{1, 2}};
    const DetectStats stats = this->world_.detect(pairs);
    EXPECT_TRUE(pairs.empty());
    EXPECT_EQ(stats.boxes, 0u);
    EXPECT_EQ(stats.pairs, 0u);
    EXPECT_EQ(this->world_.size(), 0u);
    this->check("empty again");
}

TYPED_TEST(WorldEdgeCaseTest, SingleBox) {
    this->insert(7, this->cube(0, 1));
    EXPECT_TRUE(this->check("one box").empty());
    this->update(7, this->cube(5, 5));
    this->check("one point");
    this->remove(7);
    this->check("emptied");
}

TYPED_TEST(WorldEdgeCaseTest, TwoBoxesApartThenTouchingThenOverlapping) {
    this->insert(1, this->cube(0, 1));
    this->insert(2, this->cube(2, 3));
    EXPECT_TRUE(this->check("apart").empty());
    this->update(2, this->cube(1, 3));
    EXPECT_EQ(this->check("corner touch").size(), 1u);
    this->update(2, this->cube(0.5, 3));
    EXPECT_EQ(this->check("overlapping").size(), 1u);
}

TYPED_TEST(WorldEdgeCaseTest, ManyIdenticalBoxes) {
    const std::size_t count = scaled(300);
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    for (std::size_t i = 0; i < count; ++i) {
        ids.push_back(1000 + i);
        boxes.push_back(this->cube(-1, 1));
    }
    this->insert_all(ids, boxes);
    EXPECT_EQ(this->check("identical").size(), count * (count - 1) / 2);
    this->shift_all(0.25);
    this->check("identical, moved together");
    // Half of them move away together: two identical clusters that do not meet.
    for (std::size_t i = 0; i < count; i += 2) this->update(ids[i], this->cube(10, 11));
    this->check("two identical clusters");
}

TYPED_TEST(WorldEdgeCaseTest, IdenticalPoints) {
    for (BoxId id = 0; id < 50; ++id) this->insert(id, this->cube(3, 3));
    EXPECT_EQ(this->check("coincident points").size(), 50u * 49u / 2u);
}

TYPED_TEST(WorldEdgeCaseTest, PointsOnALattice) {
    // Points on integer lattice sites, and unit boxes whose corners fall on the same sites.
    const int side = TestFixture::Dim == 2 ? 12 : 5;
    BoxId id = 0;
    std::vector<typename TestFixture::Point> sites;
    typename TestFixture::Point site{};
    const int total = TestFixture::Dim == 2 ? side * side : side * side * side;
    for (int n = 0; n < total; ++n) {
        int rest = n;
        for (int k = 0; k < TestFixture::Dim; ++k) {
            site[k] = rest % side;
            rest /= side;
        }
        sites.push_back(site);
        this->insert(id++, this->from_corners(site, site));
    }
    this->check("points only");
    for (const auto& corner : sites) {
        auto far = corner;
        for (auto& c : far) c += 1;
        this->insert(id++, this->from_corners(corner, far));
    }
    this->check("points and unit boxes on the lattice");
}

TYPED_TEST(WorldEdgeCaseTest, FlatBoxesOnSharedPlanes) {
    // Boxes of zero thickness on one axis, stacked on the planes x = 0, 1, 2, ...
    BoxId id = 0;
    for (int plane = 0; plane < 6; ++plane) {
        for (int j = 0; j < 8; ++j) {
            typename TestFixture::Point lo{};
            typename TestFixture::Point hi{};
            lo[0] = hi[0] = plane;
            for (int k = 1; k < TestFixture::Dim; ++k) {
                lo[k] = j * 0.75;
                hi[k] = lo[k] + 1.0;
            }
            this->insert(id++, this->from_corners(lo, hi));
        }
    }
    this->check("flat boxes");
    // Thicken every second plane's boxes so that they reach the neighbouring planes exactly.
    for (BoxId b = 0; b < id; ++b) {
        auto box = this->reference_.box(b);
        if (static_cast<int>(box.min[0]) % 2 == 0) {
            box.max[0] = static_cast<typename TestFixture::Real>(box.max[0] + 1);
            this->update(b, box);
        }
    }
    this->check("thickened to touch the next plane");
}

TYPED_TEST(WorldEdgeCaseTest, GridOfExactlyTouchingBoxes) {
    // Unit cells of a grid: neighbours share faces, edges and corners, all of which count.
    const int side = TestFixture::Dim == 2 ? 20 : 7;
    std::vector<typename TestFixture::BoxT> boxes;
    const int total = TestFixture::Dim == 2 ? side * side : side * side * side;
    for (int n = 0; n < total; ++n) {
        typename TestFixture::Point lo{};
        typename TestFixture::Point hi{};
        int rest = n;
        for (int k = 0; k < TestFixture::Dim; ++k) {
            lo[k] = rest % side;
            hi[k] = lo[k] + 1;
            rest /= side;
        }
        boxes.push_back(this->from_corners(lo, hi));
    }
    this->assign(boxes);
    const auto pairs = this->check("touching grid");
    // Each cell touches its 3^Dim - 1 neighbours: count the interior-inclusive total exactly.
    const std::size_t s = static_cast<std::size_t>(side);
    const std::size_t expected =
        TestFixture::Dim == 2 ? 2 * s * (s - 1) + 2 * (s - 1) * (s - 1)
                              : 3 * s * s * (s - 1) + 6 * s * (s - 1) * (s - 1) + 4 * (s - 1) * (s - 1) * (s - 1);
    EXPECT_EQ(pairs.size(), expected);
    // Shrink every box by a hair: nothing touches any more.
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (int k = 0; k < TestFixture::Dim; ++k) {
            boxes[i].min[k] = static_cast<typename TestFixture::Real>(boxes[i].min[k] + 0.25);
        }
    }
    this->assign(boxes);
    EXPECT_TRUE(this->check("shrunk grid").empty());
}

TYPED_TEST(WorldEdgeCaseTest, NegativeZeroTouchesPositiveZero) {
    using Coord = typename TestFixture::Real;
    const Coord negative_zero = -Coord(0);
    typename TestFixture::BoxT left = this->cube(-1, 1);
    typename TestFixture::BoxT right = this->cube(-1, 1);
    left.max[0] = negative_zero;
    right.min[0] = Coord(0);
    this->insert(1, left);
    this->insert(2, right);
    EXPECT_EQ(this->check("-0 against +0").size(), 1u);
    // And the other way round, plus a point box at -0.
    std::swap(left.max[0], right.min[0]);
    this->update(1, left);
    this->update(2, right);
    typename TestFixture::BoxT origin;
    for (int k = 0; k < TestFixture::Dim; ++k) origin.min[k] = origin.max[k] = negative_zero;
    this->insert(3, origin);
    this->check("+0 against -0, point at -0");
}

TYPED_TEST(WorldEdgeCaseTest, DegenerateBoxesTouchingAtACorner) {
    // The smallest scene found where a cut between tied coordinates lost a pair: boxes 1 and
    // 3 meet only at the point (1, 1, ...).
    WorldSettings settings = test_settings();
    settings.target_cell_population = 1;
    World<typename TestFixture::Real, TestFixture::Dim> world(settings);
    ReferenceWorld<typename TestFixture::Real, TestFixture::Dim> reference;
    const double corners[4][4] = {{1, 1, 0, 0}, {1, 1, 0, 1}, {0, 0, 0, 1}, {0, 1, 1, 1}};
    for (BoxId id = 0; id < 4; ++id) {
        typename TestFixture::Point lo{};
        typename TestFixture::Point hi{};
        lo[0] = corners[id][0];
        hi[0] = corners[id][1];
        lo[1] = corners[id][2];
        hi[1] = corners[id][3];
        const auto box = this->from_corners(lo, hi);
        world.insert(id, box);
        reference.insert(id, box);
    }
    EXPECT_TRUE(detects_like(world, reference));
}

TYPED_TEST(WorldEdgeCaseTest, FewDistinctCoordinateValues) {
    // Every coordinate is one of a handful of integers: ties everywhere, on every axis, and
    // many boxes of zero extent. Driven over steps that redraw some boxes, with tiny and
    // ordinary cell populations.
    for (const std::size_t population : {std::size_t{1}, std::size_t{2}, std::size_t{24}}) {
        for (const std::size_t count : {std::size_t{6}, std::size_t{20}, std::size_t{60}, scaled(250)}) {
            for (std::uint64_t seed = 1; seed <= 12; ++seed) {
                SCOPED_TRACE(::testing::Message()
                             << "population " << population << ", count " << count << ", seed " << seed);
                Random random(seed);
                const std::size_t values = 2 + seed % 3;
                const auto draw = [&random, values] {
                    typename TestFixture::Point lo{};
                    typename TestFixture::Point hi{};
                    for (int k = 0; k < TestFixture::Dim; ++k) {
                        const auto a = static_cast<double>(uniform_index(random, values));
                        const auto b = static_cast<double>(uniform_index(random, values));
                        lo[k] = std::min(a, b);
                        hi[k] = std::max(a, b);
                    }
                    return TestFixture::from_corners(lo, hi);
                };
                WorldSettings settings = test_settings();
                settings.target_cell_population = population;
                World<typename TestFixture::Real, TestFixture::Dim> world(settings);
                ReferenceWorld<typename TestFixture::Real, TestFixture::Dim> reference;
                for (BoxId id = 0; id < count; ++id) {
                    const auto box = draw();
                    world.insert(id, box);
                    reference.insert(id, box);
                }
                for (int step = 0; step < 4 && !this->HasFailure(); ++step) {
                    ASSERT_TRUE(detects_like(world, reference)) << "step " << step;
                    for (BoxId id = 0; id < count; id += 3) {
                        const auto box = draw();
                        world.update(id, box);
                        reference.update(id, box);
                    }
                }
            }
        }
    }
}

TYPED_TEST(WorldEdgeCaseTest, AllBoxesOnOnePlane) {
    Random random(1201);
    for (BoxId id = 0; id < scaled(600); ++id) {
        auto box = random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 60, 0.5, 2);
        box.min[TestFixture::Dim - 1] = 0;
        box.max[TestFixture::Dim - 1] = 0;
        this->insert(id, box);
    }
    this->check("coplanar");
    this->shift_all(0.5);
    this->check("coplanar, moved");
}

TYPED_TEST(WorldEdgeCaseTest, AllBoxesOnOneLine) {
    Random random(1301);
    for (BoxId id = 0; id < scaled(600); ++id) {
        auto box = random_box<typename TestFixture::Real, TestFixture::Dim>(random, 0, 400, 0, 2);
        for (int k = 1; k < TestFixture::Dim; ++k) {
            box.min[k] = 2;
            box.max[k] = 3;
        }
        this->insert(id, box);
    }
    this->check("collinear");
    for (int step = 0; step < 5; ++step) {
        this->shift_all(0.1);
        this->check("collinear, moving");
    }
}

TYPED_TEST(WorldEdgeCaseTest, SizesOverSixOrdersOfMagnitude) {
    Random random(1401);
    for (BoxId id = 0; id < scaled(800); ++id) {
        typename TestFixture::Point centre{};
        typename TestFixture::Point half{};
        for (int k = 0; k < TestFixture::Dim; ++k) {
            centre[k] = uniform(random, 0, 1000);
            half[k] = 0.5 * log_uniform(random, 1e-3, 1e3);
        }
        this->insert(id, box_around<typename TestFixture::Real, TestFixture::Dim>(centre, half));
    }
    this->check("sizes 1e-3 to 1e3");
    for (int step = 0; step < 5; ++step) {
        this->shift_all(step % 2 == 0 ? 3.0 : -2.0);
        this->check("moving");
    }
}

TYPED_TEST(WorldEdgeCaseTest, FloorUnderAPileOfGrains) {
    using Coord = typename TestFixture::Real;
    constexpr int dims = TestFixture::Dim;
    const std::size_t grains = scaled(20000);
    // Grains on a jittered lattice above a floor that spans the whole pile; each step they
    // fall and the ones that reach the floor rest on it exactly, as in a settling simulation.
    const auto per_row =
        static_cast<std::size_t>(std::ceil(std::pow(static_cast<double>(grains) / 10.0, 1.0 / (dims - 1))));
    Random random(1501);
    std::vector<BoxId> ids;
    std::vector<typename TestFixture::BoxT> boxes;
    typename TestFixture::Point floor_lo{};
    typename TestFixture::Point floor_hi{};
    for (int k = 0; k < dims - 1; ++k) {
        floor_lo[k] = -1;
        floor_hi[k] = static_cast<double>(per_row) + 1;
    }
    floor_lo[dims - 1] = -1;
    floor_hi[dims - 1] = 0;
    ids.push_back(0);
    boxes.push_back(this->from_corners(floor_lo, floor_hi));
    for (std::size_t g = 0; g < grains; ++g) {
        typename TestFixture::Point centre{};
        typename TestFixture::Point half{};
        std::size_t rest = g;
        for (int k = 0; k < dims - 1; ++k) {
            centre[k] = static_cast<double>(rest % per_row) + 0.5 + uniform(random, -0.1, 0.1);
            rest /= per_row;
        }
        centre[dims - 1] = 0.5 + static_cast<double>(rest) * 1.02 + uniform(random, 0, 0.3);
        for (auto& h : half) h = uniform(random, 0.3, 0.5);
        ids.push_back(g + 1);
        boxes.push_back(box_around<Coord, dims>(centre, half));
    }
    this->insert_all(ids, boxes);
    this->check("pile above the floor");
    for (int step = 0; step < 3; ++step) {
        for (std::size_t i = 1; i < boxes.size(); ++i) {
            auto& box = boxes[i];
            const Coord drop = std::min<Coord>(static_cast<Coord>(0.4), box.min[dims - 1]);
            box.min[dims - 1] = box.min[dims - 1] - drop;
            box.max[dims - 1] = box.max[dims - 1] - drop;
        }
        this->world_.update(ids, boxes);
        for (std::size_t i = 0; i < ids.size(); ++i) this->reference_.update(ids[i], boxes[i]);
        const auto pairs = this->check("grains falling onto the floor");
        std::size_t on_floor = 0;
        for (const Pair& p : pairs) on_floor += p.a == 0 ? 1 : 0;
        EXPECT_GT(on_floor, 0u);
    }
}

TYPED_TEST(WorldEdgeCaseTest, CoordinatesAcrossTheWholeRange) {
    Random random(1601);
    for (BoxId id = 0; id < scaled(800); ++id) {
        typename TestFixture::Point centre{};
        typename TestFixture::Point half{};
        for (int k = 0; k < TestFixture::Dim; ++k) {
            centre[k] = uniform(random, -1e9, 1e9);
            half[k] = log_uniform(random, 1.0, 2e8);
        }
        this->insert(id, box_around<typename TestFixture::Real, TestFixture::Dim>(centre, half));
    }
    this->insert(100000, this->cube(-1e9, 1e9));
    this->check("from -1e9 to 1e9");
    this->shift_all(1e6);
    this->check("moved by 1e6");
}

TYPED_TEST(WorldEdgeCaseTest, TinyBoxesFarFromTheOrigin) {
    // Offsets below the float spacing at 1e9 collapse to the same coordinate there; the
    // result must still match brute force on the stored values.
    Random random(1701);
    for (BoxId id = 0; id < scaled(600); ++id) {
        typename TestFixture::Point centre{};
        typename TestFixture::Point half{};
        for (int k = 0; k < TestFixture::Dim; ++k) {
            centre[k] = 1e9 + uniform(random, 0, 200);
            half[k] = uniform(random, 0, 4);
        }
        this->insert(id, box_around<typename TestFixture::Real, TestFixture::Dim>(centre, half));
    }
    this->check("near 1e9");
    this->shift_all(-2e9);
    this->check("near -1e9");
}

TYPED_TEST(WorldEdgeCaseTest, GapsAndOverlapsBelowFloatPrecision) {
    // Neighbours that touch, overlap by one unit in the last place, or miss by one, at scales
    // where float spacing is far coarser than that: the cells test floats rounded outwards
    // and must hand every such pair to the exact test (double) or test it exactly (float).
    Random random(1801);
    BoxId id = 0;
    for (const double scale : {1.0, 3.0e6, 7.0e19, 1.0e-30, -2.0e12, 1.0e300}) {
        if (std::abs(scale) * 2 > static_cast<double>(std::numeric_limits<typename TestFixture::Real>::max())) continue;
        for (std::size_t row = 0; row < scaled(60); ++row) {
            typename TestFixture::BoxT left{}, right{};
            for (int k = 0; k < TestFixture::Dim; ++k) {
                const double base = scale * (1.0 + uniform(random, 0, 1e-3)) + scale * 1e-2 * static_cast<double>(row);
                left.min[k] = static_cast<typename TestFixture::Real>(base);
                left.max[k] = static_cast<typename TestFixture::Real>(base + std::abs(scale) * 1e-4);
                right.min[k] = left.min[k];
                right.max[k] = left.max[k];
            }
            // On x only, the right box starts one step before, at, or one step after the end
            // of the left one.
            using Coord = typename TestFixture::Real;
            const Coord end = left.max[0];
            switch (row % 3) {
                case 0:
                    right.min[0] = std::nextafter(end, -std::numeric_limits<Coord>::infinity());
                    break;
                case 1:
                    right.min[0] = end;
                    break;
                default:
                    right.min[0] = std::nextafter(end, std::numeric_limits<Coord>::infinity());
                    break;
            }
            right.max[0] = std::max(right.min[0], static_cast<Coord>(end + std::abs(static_cast<double>(end)) * 1e-4));
            this->insert(id++, left);
            this->insert(id++, right);
        }
    }
    this->check("one step apart at several scales");
}

}  // namespace
}  // namespace smb::test
