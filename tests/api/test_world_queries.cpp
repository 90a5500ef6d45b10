// SPDX-License-Identifier: MIT
// World::query and World::cast_ray answer for the boxes the world holds now: checked against
// brute force over a map of the same boxes through inserts, updates, removes, assign, detect,
// clear and moves, and a world cleared and refilled.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <random>
#include <vector>

#include "reference/query_reference.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

template <class W>
class WorldQueryTest : public ::testing::Test {
protected:
    using Real = typename W::real_type;
    static constexpr int Dim = W::dimension;
    using B = Box<Real, Dim>;

    std::mt19937_64 rng{777};
    std::map<BoxId, B> truth;

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

    B random_box(double space) {
        B b;
        for (int k = 0; k < Dim; ++k) {
            const double size = uniform(0, 1) < 0.02 ? uniform(5, space) : uniform(0, 2);
            const double lo = std::round(uniform(0, space) * 2) / 2;
            b.min[k] = static_cast<Real>(lo);
            b.max[k] = static_cast<Real>(lo + std::round(size * 2) / 2);
        }
        return b;
    }

    void check(W& world, int queries, int rays) {
        std::vector<BoxId> ids;
        std::vector<B> boxes;
        for (const auto& [id, box] : truth) {
            ids.push_back(id);
            boxes.push_back(box);
        }
        for (int i = 0; i < queries; ++i) expect_query<W, Real, Dim>(world, ids, boxes, random_box(30));
        for (int i = 0; i < rays; ++i) {
            Ray<Real, Dim> ray;
            for (int k = 0; k < Dim; ++k) {
                ray.origin[k] = static_cast<Real>(std::round(uniform(-5, 35) * 2) / 2);
                ray.direction[k] = static_cast<Real>(i % 2 ? std::round(uniform(-1, 1)) : uniform(-1, 1));
            }
            if (i % 4 == 0) ray.max_t = static_cast<Real>(uniform(0, 20));
            if (!is_valid(ray)) ray.max_t = 1;
            expect_cast<W, Real, Dim>(world, ids, boxes, ray);
        }
    }
};

using WorldTypes = ::testing::Types<World2f, World2d, World3f, World3d>;
TYPED_TEST_SUITE(WorldQueryTest, WorldTypes);

TYPED_TEST(WorldQueryTest, AnswersForTheBoxesAsTheyAreNow) {
    TypeParam world;
    BoxId next = 100;
    std::vector<Pair> pairs;
    for (int step = 0; step < 12; ++step) {
        for (int i = 0; i < 60; ++i) {
            const auto box = this->random_box(30);
            world.insert(next, box);
            this->truth[next++] = box;
        }
        int n = 0;
        for (auto it = this->truth.begin(); it != this->truth.end();) {
            if (++n % 5 == 0) {
                world.remove(it->first);
                it = this->truth.erase(it);
            } else {
                if (n % 3 == 0) {
                    it->second = this->random_box(30);
                    world.update(it->first, it->second);
                }
                ++it;
            }
        }
        if (step % 3 == 1) world.detect(pairs);
        this->check(world, 30, 60);
        // Queries again without changes reuse the index and answer the same.
        this->check(world, 5, 10);
    }
}

TYPED_TEST(WorldQueryTest, AssignClearAndMove) {
    using Bt = typename TestFixture::B;
    TypeParam world;
    std::vector<Bt> boxes;
    for (int i = 0; i < 200; ++i) boxes.push_back(this->random_box(30));
    world.assign(boxes);
    for (std::size_t i = 0; i < boxes.size(); ++i) this->truth[i] = boxes[i];
    this->check(world, 20, 40);
    EXPECT_GT(world.bytes_held(), 0U);

    TypeParam moved(std::move(world));
    this->check(moved, 20, 40);
    std::vector<BoxId> out{1};
    world.query(boxes[0], out);  // a moved-from world is empty
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(world.bytes_held(), 0U);

    moved.clear();
    this->truth.clear();
    moved.query(boxes[0], out);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(moved.bytes_held(), TypeParam().bytes_held());

    boxes.resize(50);
    moved.assign(boxes);
    for (std::size_t i = 0; i < boxes.size(); ++i) this->truth[i] = boxes[i];
    this->check(moved, 20, 40);
}

// The index is current while the box store counts no change; a cleared world counts from zero
// again, so a world cleared and refilled with as many calls must not answer from the old index.
TYPED_TEST(WorldQueryTest, ClearedAndRefilledWithAsManyCalls) {
    using Bt = typename TestFixture::B;
    TypeParam world;
    std::vector<Bt> first;
    std::vector<Bt> second;
    for (int i = 0; i < 100; ++i) first.push_back(this->random_box(30));
    for (int i = 0; i < 100; ++i) second.push_back(this->random_box(30));
    std::vector<Pair> pairs;
    for (const auto* boxes : {&first, &second, &first}) {
        world.clear();
        world.assign(*boxes);  // one call since the clear, every time
        world.detect(pairs);
        this->truth.clear();
        for (std::size_t i = 0; i < boxes->size(); ++i) this->truth[i] = (*boxes)[i];
        this->check(world, 20, 20);
    }
    world.clear();
    world.insert(BoxId{7}, first[0]);
    this->truth.clear();
    this->truth[7] = first[0];
    this->check(world, 10, 10);
}

TEST(QueryDocs, TheExamplesOfDocsQueriesCompileAndAnswer) {
    std::vector<smb::Box3d> boxes{{{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {4, 1, 1}}, {{5, 5, 5}, {6, 6, 6}}};
    smb::BoxIndex3d index(boxes);
    std::vector<smb::BoxId> found;
    index.query(smb::Box3d{{0, 0, 0}, {2, 2, 2}}, found);
    EXPECT_EQ(found, std::vector<smb::BoxId>{0});
    smb::Ray3d ray{{0, 0.5, 0.5}, {1, 0, 0}, 50};
    std::vector<smb::RayHit<double>> hits;
    index.cast_ray(ray, smb::RayHits::nearest, hits);
    ASSERT_EQ(hits.size(), 1U);
    EXPECT_EQ(hits[0], (smb::RayHit<double>{0, 0}));
    index.cast_ray(smb::Ray3d::segment({0, 0, 0}, {9, 9, 9}), smb::RayHits::all, hits);
    ASSERT_EQ(hits.size(), 2U);
    EXPECT_EQ(hits[0], (smb::RayHit<double>{0, 0}));
    EXPECT_EQ(hits[1].id, 2U);
    EXPECT_DOUBLE_EQ(hits[1].t, 5.0 / 9.0);

    smb::World3d world;
    world.insert(7, boxes[0]);
    world.insert(9, boxes[1]);
    std::vector<smb::QueryHit> batch;
    world.query(std::vector<smb::Box3d>{{{3.5, 0, 0}, {3.5, 0, 0}}, {{0, 0, 0}, {9, 9, 9}}}, batch);
    std::sort(batch.begin(), batch.end());  // within one query the order is unspecified
    EXPECT_EQ(batch, (std::vector<smb::QueryHit>{{0, 9}, {1, 7}, {1, 9}}));
}

}  // namespace
}  // namespace smb::test
