// SPDX-License-Identifier: MIT
// World's periodic detection against the brute force over the 3^D images: random scenes over
// many steps with motion across the boundary, insertions, removals, teleports and ids of any
// size; one and two threads; events through boundary crossings and reinsertions; periodic
// and ordinary detections alternating; rejected input.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "reference/periodic_brute_force.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

template <class T>
class PeriodicWorldTest : public ::testing::Test {};

TYPED_TEST_SUITE(PeriodicWorldTest, WorldTypes, WorldTypeNames);

/// The world's boxes and ids, for the brute force.
template <class World>
struct Scene {
    std::vector<BoxId> ids;
    std::vector<typename World::box_type> boxes;
    std::unordered_map<BoxId, std::size_t> at;

    void insert(World& world, BoxId id, const typename World::box_type& box) {
        world.insert(id, box);
        at[id] = ids.size();
        ids.push_back(id);
        boxes.push_back(box);
    }
    void remove(World& world, std::size_t i) {
        world.remove(ids[i]);
        at.erase(ids[i]);
        if (i + 1 != ids.size()) {
            ids[i] = ids.back();
            boxes[i] = boxes.back();
            at[ids[i]] = i;
        }
        ids.pop_back();
        boxes.pop_back();
    }
    std::vector<PeriodicPair> brute(const PeriodicDomain<typename World::real_type, World::dimension>& domain) const {
        return brute_force_periodic_pairs<typename World::real_type, World::dimension>(boxes, ids, domain);
    }
};

TYPED_TEST(PeriodicWorldTest, RandomScenesWithInsertionsRemovalsAndTeleports) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    const double side = 20;
    const unsigned all = (1u << Dim) - 1;
    for (const unsigned axes : {all, 2u}) {
        Random random(500 + axes);
        const auto domain = cube_domain<Real, Dim>(side, axes);
        WorldSettings two;
        two.threads = 2;
        two.target_cell_population = 6;
        WorldSettings skin;  // the skin list keeps the candidates of the boxes and their images
        skin.skin = 0.4;
        World world;
        World threaded(two);
        World skinned(skin);
        Scene<World> scene;
        BoxId next = 1;
        auto new_id = [&] {
            // Ids far apart, some beyond 2^63, so that names and indices never coincide.
            next += 1 + uniform_index(random, 1000);
            return chance(random, 0.2) ? next | (BoxId{1} << 63) : next;
        };
        for (std::size_t i = 0; i < scaled(300); ++i) {
            const auto box = particle_box<Real, Dim>(random, side, 0.2, 3.0);
            const BoxId id = new_id();
            scene.insert(world, id, box);
            threaded.insert(id, box);
            skinned.insert(id, box);
        }
        std::vector<PeriodicPair> pairs;
        std::vector<PeriodicPair> pairs_threaded;
        std::vector<PeriodicPair> pairs_skinned;
        for (int step = 0; step < 14; ++step) {
            SCOPED_TRACE("axes " + std::to_string(axes) + ", step " + std::to_string(step));
            world.detect(domain, pairs);
            threaded.detect(domain, pairs_threaded);
            skinned.detect(domain, pairs_skinned);
            const auto expected = scene.brute(domain);
            ASSERT_TRUE(same_periodic_pairs(pairs, expected));
            ASSERT_TRUE(same_periodic_pairs(pairs_threaded, expected));
            ASSERT_TRUE(same_periodic_pairs(pairs_skinned, expected));
            for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
                scene.boxes[i] = moved(random, scene.boxes[i], domain, 0.3, chance(random, 0.03));
                if (chance(random, 0.01))  // a teleport, maybe periods away
                    scene.boxes[i] = translated(particle_box<Real, Dim>(random, side, 0.2, 3.0), domain,
                                                static_cast<int>(uniform_index(random, 5)) - 2);
            }
            world.update(scene.ids, scene.boxes);
            threaded.update(scene.ids, scene.boxes);
            skinned.update(scene.ids, scene.boxes);
            for (int r = 0; r < 15 && !scene.ids.empty(); ++r) {
                const std::size_t i = uniform_index(random, scene.ids.size());
                threaded.remove(scene.ids[i]);
                skinned.remove(scene.ids[i]);
                scene.remove(world, i);
            }
            for (int n = 0; n < 15; ++n) {
                const auto box = particle_box<Real, Dim>(random, side, 0.2, 3.0);
                const BoxId id = new_id();
                scene.insert(world, id, box);
                threaded.insert(id, box);
                skinned.insert(id, box);
            }
        }
    }
}

TYPED_TEST(PeriodicWorldTest, EventsFollowPairsAcrossTheBoundary) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    const double side = 12;
    Random random(77);
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    World world;
    Scene<World> scene;
    for (BoxId id = 0; id < scaled(300); ++id)
        scene.insert(world, id * 3, particle_box<Real, Dim>(random, side, 0.3, 2));
    PairEvents events;
    std::vector<PeriodicPair> pairs;
    std::vector<PeriodicPair> before;
    std::size_t crossings = 0;
    for (int step = 0; step < 16; ++step) {
        world.detect(domain, pairs, events);
        ASSERT_TRUE(same_periodic_pairs(pairs, scene.brute(domain)));
        // The events are the differences of the (a, b) sets: a changed shift is no event.
        std::vector<Pair> now;
        std::vector<Pair> then;
        for (const auto& p : pairs) now.push_back(Pair{p.a, p.b});
        for (const auto& p : before) then.push_back(Pair{p.a, p.b});
        std::sort(now.begin(), now.end());
        std::sort(then.begin(), then.end());
        std::vector<Pair> begun;
        std::vector<Pair> ended;
        std::set_difference(now.begin(), now.end(), then.begin(), then.end(), std::back_inserter(begun));
        std::set_difference(then.begin(), then.end(), now.begin(), now.end(), std::back_inserter(ended));
        if (step == 5) {
            // Box 0 removed and inserted again: a new box, whose pairs all end and begin.
            ASSERT_TRUE(scene.at.count(0));
            for (const Pair& p : then) {
                if ((p.a == 0 || p.b == 0) && std::binary_search(now.begin(), now.end(), p)) {
                    begun.push_back(p);
                    ended.push_back(p);
                }
            }
            std::sort(begun.begin(), begun.end());
            std::sort(ended.begin(), ended.end());
        }
        EXPECT_EQ(std::vector<Pair>(events.begun().begin(), events.begun().end()), begun) << "step " << step;
        EXPECT_EQ(std::vector<Pair>(events.ended().begin(), events.ended().end()), ended) << "step " << step;
        for (const auto& p : pairs) {
            for (const auto& q : before) crossings += (p.a == q.a && p.b == q.b && p.shift != q.shift) ? 1 : 0;
        }
        before = pairs;
        for (auto& box : scene.boxes) box = moved(random, box, domain, 0.4, false);
        world.update(scene.ids, scene.boxes);
        if (step == 4) {
            const auto box = scene.boxes[scene.at[0]];
            world.remove(0);
            world.insert(0, box);
        }
    }
    EXPECT_GT(crossings, 0u) << "no pair changed its shift: the scene did not test crossings";
}

TYPED_TEST(PeriodicWorldTest, PeriodicAndOrdinaryDetectionsAlternate) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    Random random(8);
    const double side = 15;
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    World world;
    Scene<World> scene;
    for (BoxId id = 0; id < scaled(300); ++id) scene.insert(world, id, particle_box<Real, Dim>(random, side, 0.3, 2));
    std::vector<PeriodicPair> periodic;
    std::vector<Pair> plain;
    for (int step = 0; step < 6; ++step) {
        if (step % 2 == 0) {
            world.detect(domain, periodic);
            EXPECT_TRUE(same_periodic_pairs(periodic, scene.brute(domain)));
        } else {
            world.detect(plain);
            std::vector<PeriodicPair> as_periodic;
            for (const Pair& p : plain) as_periodic.push_back(PeriodicPair{p.a, p.b, {}});
            EXPECT_TRUE(same_periodic_pairs(as_periodic, scene.brute(PeriodicDomain<Real, Dim>{})));
        }
        for (auto& box : scene.boxes) box = moved(random, box, domain, 0.4, false);
        world.update(scene.ids, scene.boxes);
        scene.remove(world, uniform_index(random, scene.ids.size()));
    }
}

TYPED_TEST(PeriodicWorldTest, AnEmptyWorld) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    World world;
    std::vector<PeriodicPair> pairs{PeriodicPair{1, 2, {}}};
    world.detect(cube_domain<Real, Dim>(4, 3), pairs);
    EXPECT_TRUE(pairs.empty());
    world.insert(5, typename World::box_type{});
    world.insert(6, typename World::box_type{});
    world.detect(cube_domain<Real, Dim>(4, 3), pairs);
    ASSERT_EQ(pairs.size(), 1u);
    EXPECT_EQ(pairs[0], (PeriodicPair{5, 6, {}}));
    world.clear();
    world.detect(cube_domain<Real, Dim>(4, 3), pairs);
    EXPECT_TRUE(pairs.empty());
}

TYPED_TEST(PeriodicWorldTest, RejectedInputChangesNothing) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    Random random(9);
    const auto domain = cube_domain<Real, Dim>(10, (1u << Dim) - 1);
    World world;
    Scene<World> scene;
    for (BoxId id = 0; id < 60; ++id) scene.insert(world, id + 100, particle_box<Real, Dim>(random, 10, 0.3, 2));
    std::vector<PeriodicPair> pairs;
    world.detect(domain, pairs);
    const auto before = pairs;

    // A box too large for the domain: refused, named by its id.
    auto big = scene.boxes[7];
    big.max[0] = big.min[0] + Real(6);
    world.update(scene.ids[7], big);
    try {
        world.detect(domain, pairs);
        ADD_FAILURE() << "no throw";
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("box " + std::to_string(scene.ids[7])), std::string::npos)
            << error.what();
    }
    EXPECT_EQ(pairs, before);
    // Removed, it no longer counts.
    world.remove(scene.ids[7]);
    world.detect(domain, pairs);
    world.insert(scene.ids[7], scene.boxes[7]);

    auto reversed = domain;
    std::swap(reversed.lo[0], reversed.hi[0]);
    auto nan = domain;
    nan.hi[0] = std::numeric_limits<Real>::quiet_NaN();
    std::vector<PeriodicPair> kept = pairs;
    EXPECT_THROW(world.detect(reversed, pairs), ArgumentError);
    EXPECT_THROW(world.detect(nan, pairs), ArgumentError);
    EXPECT_EQ(pairs, kept);
    world.set_filter(scene.ids[0], Filter{2, 2});
    EXPECT_THROW(world.detect(domain, pairs), ArgumentError);
    world.set_filter(scene.ids[0], Filter{});
    world.detect(domain, pairs);
    EXPECT_TRUE(same_periodic_pairs(pairs, before));
    EXPECT_EQ(world.size(), scene.ids.size());
}

}  // namespace
}  // namespace smb::test
