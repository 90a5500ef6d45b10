// SPDX-License-Identifier: MIT
// smb::BoxIndex against brute force: random scenes of mixed sizes (tiny, flat, huge), a lattice
// whose faces lie on the grid's cell boundaries, far coordinates; box queries and rays of every
// awkward kind (along faces, through corners and edges, axis-parallel, zero-length, starting
// inside boxes, max_t exactly reaching a face).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "reference/query_reference.hpp"
#include "smb/box_index.hpp"

namespace smb::test {
namespace {

template <class Real, int D>
struct Types {
    using real = Real;
    static constexpr int dim = D;
};

template <class T>
class BoxIndexTest : public ::testing::Test {
protected:
    using Real = typename T::real;
    static constexpr int Dim = T::dim;
    using B = Box<Real, Dim>;
    using R = Ray<Real, Dim>;
    using Point = std::array<Real, Dim>;

    std::mt19937_64 rng{12345};
    std::vector<B> boxes;
    std::vector<BoxId> ids;

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
    std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); }
    bool chance(double p) { return uniform(0, 1) < p; }

    void set_ids() {
        ids.resize(boxes.size());
        // Ids unrelated to positions, to catch an index reporting positions.
        for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = 1000003ULL * i + 17;
    }

    B box_at(const std::array<double, Dim>& lo, const std::array<double, Dim>& size) {
        B b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = static_cast<Real>(lo[k]);
            b.max[k] = static_cast<Real>(lo[k] + size[k]);
            if (b.max[k] < b.min[k]) b.max[k] = b.min[k];
        }
        return b;
    }

    /// Mixed sizes in [0, space]^Dim; half the boxes snapped to quarters, so faces coincide.
    void mixed_scene(std::size_t n, double space) {
        boxes.clear();
        for (std::size_t i = 0; i < n; ++i) {
            std::array<double, Dim> lo{};
            std::array<double, Dim> size{};
            const double kind = uniform(0, 1);
            for (int k = 0; k < Dim; ++k) {
                if (kind < 0.8)
                    size[k] = uniform(0.5, 2);
                else if (kind < 0.9)
                    size[k] = uniform(0, 1e-5);
                else if (kind < 0.95)
                    size[k] = k == 0 ? 0 : uniform(0.5, 3);
                else if (kind < 0.99)
                    size[k] = uniform(5, 30);
                else
                    size[k] = space;
                lo[k] = uniform(0, space - size[k]);
            }
            if (chance(0.5)) {
                for (int k = 0; k < Dim; ++k) {
                    lo[k] = std::round(lo[k] * 4) / 4;
                    size[k] = std::round(size[k] * 4) / 4;
                }
            }
            boxes.push_back(box_at(lo, size));
        }
        set_ids();
    }

    /// Unit boxes on the integer lattice, about 70% of the sites: every face on a cell boundary.
    void lattice_scene(int side) {
        boxes.clear();
        std::array<int, 3> c{};
        for (c[2] = 0; c[2] < (Dim == 3 ? side : 1); ++c[2]) {
            for (c[1] = 0; c[1] < side; ++c[1]) {
                for (c[0] = 0; c[0] < side; ++c[0]) {
                    if (!chance(0.7)) continue;
                    std::array<double, Dim> lo{};
                    std::array<double, Dim> size{};
                    for (int k = 0; k < Dim; ++k) {
                        lo[k] = c[static_cast<std::size_t>(k)];
                        size[k] = 1;
                    }
                    boxes.push_back(box_at(lo, size));
                }
            }
        }
        set_ids();
    }

    Point random_point(double lo, double hi, bool snapped) {
        Point p{};
        for (int k = 0; k < Dim; ++k) {
            double v = uniform(lo, hi);
            if (snapped) v = std::round(v * 4) / 4;
            p[k] = static_cast<Real>(v);
        }
        return p;
    }

    Point corner(const B& b) {
        Point p{};
        for (int k = 0; k < Dim; ++k) p[k] = chance(0.5) ? b.min[k] : b.max[k];
        return p;
    }

    /// A ray of one of the awkward kinds, numbered by `kind`.
    R awkward_ray(int kind, double space) {
        R ray;
        const B& b = boxes[pick(boxes.size())];
        const int axis = static_cast<int>(pick(Dim));
        const Real sign = chance(0.5) ? Real(1) : Real(-1);
        switch (kind % 8) {
            case 0:  // anywhere, any direction, any length
                ray.origin = random_point(-0.2 * space, 1.2 * space, false);
                for (int k = 0; k < Dim; ++k) ray.direction[k] = static_cast<Real>(uniform(-1, 1));
                if (chance(0.5)) ray.max_t = static_cast<Real>(uniform(0, space));
                break;
            case 1:  // axis-parallel, along a face or edge of a box
                ray.origin = corner(b);
                ray.origin[axis] = static_cast<Real>(chance(0.5) ? uniform(-0.2 * space, 1.2 * space) : -space);
                ray.direction[axis] = sign;
                break;
            case 2:  // through a corner of a box
                ray.origin = random_point(-0.2 * space, 1.2 * space, chance(0.5));
                for (int k = 0; k < Dim; ++k) ray.direction[k] = corner(b)[k] - ray.origin[k];
                if (chance(0.5)) ray.max_t = 1;  // exactly reaching it
                break;
            case 3:  // zero-length segment at a corner or anywhere
                ray.origin = chance(0.5) ? corner(b) : random_point(0, space, true);
                ray.max_t = chance(0.5) ? Real(0) : Real(1);
                break;
            case 4:  // starting inside a box
                for (int k = 0; k < Dim; ++k) {
                    ray.origin[k] = static_cast<Real>((static_cast<double>(b.min[k]) + b.max[k]) / 2);
                    ray.direction[k] = static_cast<Real>(uniform(-1, 1));
                }
                break;
            case 5: {  // axis-parallel, max_t exactly reaching a face
                ray.origin = corner(b);
                const Real face = ray.origin[axis];
                ray.origin[axis] = static_cast<Real>(std::round(uniform(-0.2 * space, 1.2 * space)));
                ray.direction[axis] = face >= ray.origin[axis] ? Real(1) : Real(-1);
                ray.max_t = std::abs(face - ray.origin[axis]);
                break;
            }
            case 6:  // a diagonal through lattice or quarter points
                ray.origin = random_point(-0.2 * space, 1.2 * space, true);
                for (int k = 0; k < Dim; ++k) ray.direction[k] = chance(0.5) ? Real(1) : Real(-1);
                if (chance(0.3)) ray.direction[pick(Dim)] = 0;
                break;
            default: {  // a segment between two corners
                const B& other = boxes[pick(boxes.size())];
                ray = R::segment(corner(b), corner(other));
                break;
            }
        }
        return ray;
    }

    B random_query(double space) {
        const double kind = uniform(0, 1);
        if (kind < 0.2) return boxes[pick(boxes.size())];
        std::array<double, Dim> lo{};
        std::array<double, Dim> size{};
        for (int k = 0; k < Dim; ++k) {
            lo[k] = uniform(-0.1 * space, 1.1 * space);
            size[k] = kind < 0.3 ? 0 : kind < 0.9 ? uniform(0, 4) : uniform(0, 2 * space);
            if (kind < 0.6) {
                lo[k] = std::round(lo[k] * 4) / 4;
                size[k] = std::round(size[k] * 4) / 4;
            }
        }
        return box_at(lo, size);
    }

    void check_all(int queries, int rays, double space) {
        BoxIndex<Real, Dim> index(ids, boxes);
        ASSERT_EQ(index.size(), boxes.size());
        std::vector<B> batch;
        for (int i = 0; i < queries; ++i) {
            batch.push_back(random_query(space));
            expect_query<BoxIndex<Real, Dim>, Real, Dim>(index, ids, boxes, batch.back());
        }
        std::vector<QueryHit> hits;
        index.query(batch, hits);
        std::vector<BoxId> single;
        std::size_t at = 0;
        for (std::size_t q = 0; q < batch.size(); ++q) {
            index.query(batch[q], single);
            for (const BoxId id : single) {
                ASSERT_LT(at, hits.size());
                ASSERT_EQ(hits[at], (QueryHit{q, id}));
                ++at;
            }
        }
        ASSERT_EQ(at, hits.size());
        for (int i = 0; i < rays; ++i) {
            expect_cast<BoxIndex<Real, Dim>, Real, Dim>(index, ids, boxes, awkward_ray(i, space));
        }
    }
};

using AllTypes = ::testing::Types<Types<float, 2>, Types<double, 2>, Types<float, 3>, Types<double, 3>>;
TYPED_TEST_SUITE(BoxIndexTest, AllTypes);

TYPED_TEST(BoxIndexTest, MixedSizesAgainstBruteForce) {
    for (int scene = 0; scene < 3; ++scene) {
        this->mixed_scene(1500, 64);
        this->check_all(300, 1600, 64);
    }
}

TYPED_TEST(BoxIndexTest, LatticeFacesOnCellBoundaries) {
    this->lattice_scene(TestFixture::Dim == 3 ? 12 : 40);
    this->check_all(300, 2400, TestFixture::Dim == 3 ? 12 : 40);
}

TYPED_TEST(BoxIndexTest, FarCoordinatesHugeAndTiny) {
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    this->mixed_scene(800, 64);
    // Spread the scene to about a million units while keeping tiny boxes tiny, and add a few
    // boxes that span it all.
    for (auto& b : this->boxes) {
        for (int k = 0; k < Dm; ++k) {
            const Rt shift = static_cast<Rt>(std::round(b.min[k] * 16000.0));
            b.max[k] = static_cast<Rt>(shift + (b.max[k] - b.min[k]));
            b.min[k] = shift;
        }
    }
    for (int i = 0; i < 3; ++i) {
        Box<Rt, Dm> huge;
        for (int k = 0; k < Dm; ++k) {
            huge.min[k] = static_cast<Rt>(-1e6 * (i + 1));
            huge.max[k] = static_cast<Rt>(k == i % Dm ? -1e6 * (i + 1) : 2e6);
        }
        this->boxes.push_back(huge);
    }
    this->set_ids();
    this->check_all(200, 1600, 1.024e6);
}

TYPED_TEST(BoxIndexTest, SubnormalScene) {
    // A scene a few hundred subnormals wide: the cell side would round to 0 or have no finite
    // inverse, and the index must still answer exactly (one cell, unindexed).
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    this->mixed_scene(200, 64);
    const Rt tiny = std::numeric_limits<Rt>::denorm_min() * 4;
    for (auto& b : this->boxes) {
        for (int k = 0; k < Dm; ++k) {
            b.min[k] = std::round(b.min[k]) * tiny;
            b.max[k] = std::max(b.min[k], std::round(b.max[k]) * tiny);
        }
    }
    this->set_ids();
    this->check_all(50, 200, 64 * static_cast<double>(tiny));
}

TYPED_TEST(BoxIndexTest, DegenerateScenes) {
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    using Bt = Box<Rt, Dm>;
    // All boxes identical; all points; all on one plane; a single box.
    this->boxes.assign(50, Bt{});
    for (auto& b : this->boxes) b.max.fill(1);
    this->set_ids();
    this->check_all(50, 200, 1);
    this->boxes.assign(60, Bt{});
    for (std::size_t i = 0; i < this->boxes.size(); ++i) {
        for (int k = 0; k < Dm; ++k) this->boxes[i].min[k] = this->boxes[i].max[k] = static_cast<Rt>((i * (k + 3)) % 7);
    }
    this->set_ids();
    this->check_all(100, 400, 7);
    this->mixed_scene(400, 16);
    for (auto& b : this->boxes) b.min[Dm - 1] = b.max[Dm - 1] = 2;
    this->set_ids();
    this->check_all(100, 800, 16);
    this->boxes.assign(1, Bt{});
    this->boxes[0].max.fill(3);
    this->set_ids();
    this->check_all(20, 200, 3);
    if constexpr (std::is_same_v<Rt, double>) {
        // A scene whose extent overflows double: boxes near both ends of its range.
        this->mixed_scene(100, 16);
        this->boxes[0].min.fill(-1.7e308);
        this->boxes[1].max.fill(1.7e308);
        this->boxes[1].min.fill(1e308);
        this->set_ids();
        this->check_all(50, 400, 16);
        // A scene near one end of the range, rays from the other: grid coordinates overflow.
        this->mixed_scene(100, 16);
        for (auto& b : this->boxes) {
            for (int k = 0; k < Dm; ++k) {
                b.min[k] = b.min[k] * 1e292 + 1.6e308;
                b.max[k] = b.max[k] * 1e292 + 1.6e308;
            }
        }
        this->set_ids();
        BoxIndex<Rt, Dm> index(this->ids, this->boxes);
        for (int i = 0; i < 100; ++i) {
            Ray<Rt, Dm> ray;
            for (int k = 0; k < Dm; ++k) {
                ray.origin[k] = -1.5e308;
                // Half the way to a random point of the scene (the whole way overflows), twice.
                ray.direction[k] = (1.6e308 + this->uniform(0, 16) * 1e292) / 2 + 0.75e308;
            }
            ray.max_t = 2;
            expect_cast<BoxIndex<Rt, Dm>, Rt, Dm>(index, this->ids, this->boxes, ray);
        }
    }
}

TYPED_TEST(BoxIndexTest, EmptyIndexAnswersNothing) {
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    BoxIndex<Rt, Dm> index;
    std::vector<BoxId> out{1, 2};
    index.query(Box<Rt, Dm>{}, out);
    EXPECT_TRUE(out.empty());
    std::vector<RayHit<Rt>> hits{{1, 0}};
    Ray<Rt, Dm> ray;
    ray.direction[0] = 1;
    index.cast_ray(ray, RayHits::all, hits);
    EXPECT_TRUE(hits.empty());
    index = BoxIndex<Rt, Dm>(std::vector<Box<Rt, Dm>>{});
    index.cast_ray(ray, RayHits::nearest, hits);
    EXPECT_TRUE(hits.empty());
    EXPECT_EQ(index.size(), 0U);
}

TYPED_TEST(BoxIndexTest, NearestTiesGoToTheLeastId) {
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    std::vector<Box<Rt, Dm>> same(5);
    for (auto& b : same) {
        b.min.fill(2);
        b.max.fill(3);
    }
    const std::vector<BoxId> repeated{9, 4, 7, 4, 11};
    BoxIndex<Rt, Dm> index(repeated, same);
    Ray<Rt, Dm> ray;
    ray.origin.fill(Rt(2.5));
    ray.origin[0] = 0;
    ray.direction[0] = 2;
    std::vector<RayHit<Rt>> hits;
    index.cast_ray(ray, RayHits::nearest, hits);
    ASSERT_EQ(hits.size(), 1U);
    EXPECT_EQ(hits[0].id, 4U);
    EXPECT_EQ(hits[0].t, Rt(1));
    index.cast_ray(ray, RayHits::all, hits);
    ASSERT_EQ(hits.size(), 5U);  // a repeated id is reported once per box
    EXPECT_EQ(hits[0].id, 4U);
    EXPECT_EQ(hits[1].id, 4U);
    EXPECT_EQ(hits[4].id, 11U);
    ray.max_t = Rt(0.5);  // stops short of the face at t = 1
    index.cast_ray(ray, RayHits::all, hits);
    EXPECT_TRUE(hits.empty());
    ray.max_t = 1;  // exactly reaching it
    index.cast_ray(ray, RayHits::all, hits);
    EXPECT_EQ(hits.size(), 5U);
}

TYPED_TEST(BoxIndexTest, HitsAreOrderedByTheReportedT) {
    using Rt = typename TestFixture::Real;
    constexpr int Dm = TestFixture::Dim;
    // Faces one ulp apart, entered at t that differ in double but may round to the same Real;
    // ids descending, so that (t, id) order and double order disagree where they tie.
    std::vector<Box<Rt, Dm>> faces;
    std::vector<BoxId> descending;
    Rt x = 1;
    for (int i = 0; i < 40; ++i) {
        Box<Rt, Dm> b;
        b.min.fill(0);
        b.max.fill(1);
        b.min[0] = x;
        b.max[0] = 2;
        faces.push_back(b);
        descending.push_back(static_cast<BoxId>(100 - i));
        x = std::nextafter(x, Rt(2));
    }
    BoxIndex<Rt, Dm> index(descending, faces);
    Ray<Rt, Dm> ray;
    ray.origin.fill(Rt(0.5));
    ray.origin[0] = Rt(-0.3);
    ray.direction[0] = Rt(3);
    std::vector<RayHit<Rt>> all;
    std::vector<RayHit<Rt>> nearest;
    index.cast_ray(ray, RayHits::all, all);
    index.cast_ray(ray, RayHits::nearest, nearest);
    ASSERT_EQ(all.size(), faces.size());
    for (std::size_t i = 1; i < all.size(); ++i) {
        ASSERT_TRUE(all[i - 1].t < all[i].t || (all[i - 1].t == all[i].t && all[i - 1].id < all[i].id)) << i;
    }
    ASSERT_EQ(nearest.size(), 1U);
    EXPECT_EQ(nearest[0], all[0]);
    this->boxes = faces;
    this->ids = descending;
    expect_cast<BoxIndex<Rt, Dm>, Rt, Dm>(index, this->ids, this->boxes, ray);
}

TYPED_TEST(BoxIndexTest, RebuildReplacesTheBoxes) {
    // A rebuild reuses the index's arrays: larger, then smaller, then empty, then again.
    BoxIndex<typename TestFixture::Real, TestFixture::Dim> index;
    for (const std::size_t n : {300U, 1200U, 40U, 0U, 500U}) {
        this->mixed_scene(n, 20);
        index.build(this->ids, this->boxes);
        ASSERT_EQ(index.size(), n);
        for (int i = 0; i < 50 && n != 0; ++i) {
            expect_query<BoxIndex<typename TestFixture::Real, TestFixture::Dim>, typename TestFixture::Real,
                         TestFixture::Dim>(index, this->ids, this->boxes, this->random_query(20));
            expect_cast<BoxIndex<typename TestFixture::Real, TestFixture::Dim>, typename TestFixture::Real,
                        TestFixture::Dim>(index, this->ids, this->boxes, this->awkward_ray(i, 20));
        }
    }
}

}  // namespace
}  // namespace smb::test
