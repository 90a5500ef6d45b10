// SPDX-License-Identifier: MIT
// Bad input to BoxIndex and to World's queries: a clear error, and nothing changed (the index,
// the world, the caller's vector).

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "smb/box_index.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<Box3d> two_boxes() { return {Box3d{{0, 0, 0}, {1, 1, 1}}, Box3d{{2, 0, 0}, {3, 1, 1}}}; }

Ray3d along_x() {
    Ray3d ray;
    ray.origin = {-1, 0.5, 0.5};
    ray.direction = {1, 0, 0};
    return ray;
}

template <class Call>
std::string message_of(Call&& call) {
    try {
        call();
    } catch (const Error& error) {
        return error.what();
    }
    return "no error";
}

TEST(QueryErrors, InvalidRaysAreRefusedAndChangeNothing) {
    const BoxIndex3d index(two_boxes());
    const std::vector<RayHit<double>> before{{42, 0.5}};
    struct Case {
        Ray3d ray;
        const char* says;
    };
    std::vector<Case> cases;
    Ray3d r = along_x();
    r.origin[1] = kNaN;
    cases.push_back({r, "origin is not finite"});
    r = along_x();
    r.origin[0] = -kInf;
    cases.push_back({r, "origin is not finite"});
    r = along_x();
    r.direction[2] = kInf;
    cases.push_back({r, "direction is not finite"});
    r = along_x();
    r.direction[0] = kNaN;
    cases.push_back({r, "direction is not finite"});
    r = along_x();
    r.max_t = -1;
    cases.push_back({r, "max_t must be >= 0"});
    r = along_x();
    r.max_t = kNaN;
    cases.push_back({r, "max_t must be >= 0"});
    r = along_x();
    r.direction = {0, 0, 0};  // a zero direction with an infinite max_t
    cases.push_back({r, "zero direction"});
    for (const Case& c : cases) {
        EXPECT_FALSE(is_valid(c.ray));
        for (const RayHits mode : {RayHits::nearest, RayHits::all}) {
            std::vector<RayHit<double>> hits = before;
            EXPECT_THROW(index.cast_ray(c.ray, mode, hits), ArgumentError);
            EXPECT_EQ(hits, before);
            const std::string message = message_of([&] { index.cast_ray(c.ray, mode, hits); });
            EXPECT_NE(message.find(c.says), std::string::npos) << message;
            EXPECT_NE(message.find("cast_ray"), std::string::npos) << message;
        }
    }
}

TEST(QueryErrors, ZeroLengthSegmentIsAPoint) {
    const BoxIndex3d index(two_boxes());
    Ray3d point = Ray3d::segment({1, 0.5, 1}, {1, 0.5, 1});  // on the first box's corner edge
    ASSERT_TRUE(is_valid(point));
    std::vector<RayHit<double>> hits;
    index.cast_ray(point, RayHits::all, hits);
    ASSERT_EQ(hits.size(), 1U);
    EXPECT_EQ(hits[0], (RayHit<double>{0, 0}));
    point.max_t = 0;
    index.cast_ray(point, RayHits::nearest, hits);
    EXPECT_EQ(hits.size(), 1U);
    point.origin = {1.5, 0.5, 0.5};
    index.cast_ray(point, RayHits::all, hits);
    EXPECT_TRUE(hits.empty());
    // A ray of max_t 0 with a direction is the same point.
    Ray3d ray = along_x();
    ray.origin = {2, 0, 0};
    ray.max_t = 0;
    index.cast_ray(ray, RayHits::all, hits);
    EXPECT_EQ(hits.size(), 1U);
}

TEST(QueryErrors, InvalidQueryBoxesAreRefusedAndChangeNothing) {
    const BoxIndex3d index(two_boxes());
    const std::vector<Box3d> bad{Box3d{{0, 0, kNaN}, {1, 1, 1}}, Box3d{{0, 0, 0}, {kInf, 1, 1}},
                                 Box3d{{0, 2, 0}, {1, 1, 1}}};
    for (const Box3d& box : bad) {
        std::vector<BoxId> out{5};
        EXPECT_THROW(index.query(box, out), InvalidBoxError);
        EXPECT_EQ(out, std::vector<BoxId>{5});
        // In a batch, the message names the query's index; the hits stay as they were.
        const std::vector<Box3d> batch{Box3d{{0, 0, 0}, {1, 1, 1}}, box};
        std::vector<QueryHit> hits{{7, 7}};
        const std::string message = message_of([&] { index.query(batch, hits); });
        EXPECT_NE(message.find("query 1 is invalid"), std::string::npos) << message;
        EXPECT_EQ(hits, (std::vector<QueryHit>{{7, 7}}));
    }
}

TEST(QueryErrors, InvalidBuildKeepsTheIndex) {
    BoxIndex3d index(two_boxes());
    std::vector<Box3d> bad = two_boxes();
    bad[1].min[0] = 5;  // min > max
    EXPECT_THROW(index.build(bad), InvalidBoxError);
    const std::vector<BoxId> ids{1};
    EXPECT_THROW(index.build(ids, two_boxes()), ArgumentError);
    EXPECT_EQ(index.size(), 2U);
    std::vector<BoxId> out;
    index.query(Box3d{{0, 0, 0}, {5, 5, 5}}, out);
    EXPECT_EQ(out.size(), 2U);
}

TEST(QueryErrors, WorldQueriesRefuseBadInputAndChangeNothing) {
    World3d world;
    world.insert(10, Box3d{{0, 0, 0}, {1, 1, 1}});
    Ray3d ray = along_x();
    ray.max_t = -0.5;
    std::vector<RayHit<double>> hits{{1, 1}};
    EXPECT_THROW(world.cast_ray(ray, RayHits::all, hits), ArgumentError);
    EXPECT_EQ(hits.size(), 1U);
    std::vector<BoxId> out{3};
    EXPECT_THROW(world.query(Box3d{{1, 0, 0}, {0, 1, 1}}, out), InvalidBoxError);
    EXPECT_EQ(out, std::vector<BoxId>{3});
    EXPECT_EQ(world.size(), 1U);
    world.query(Box3d{{1, 1, 1}, {2, 2, 2}}, out);
    EXPECT_EQ(out, std::vector<BoxId>{10});
}

}  // namespace
}  // namespace smb::test
