// SPDX-License-Identifier: MIT
// Ids across the whole 64-bit range on every path that carries them: World's detections (with
// events), periodic detections, filters, static boxes and the predicate, region queries and ray
// casts, and PairEvents on their own. The ids include the edges where a narrowing or a packing
// of ids would show: 2^31, 2^32 - 1, 2^32, 2^63 - 1, 2^63, 2^64 - 1, and ids that differ only
// above bit 31 or bit 32. Each path against brute force over many steps with moves, teleports,
// insertions and removals.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/pair_check.hpp"
#include "reference/periodic_brute_force.hpp"
#include "reference/random_boxes.hpp"
#include "smb/pair_events.hpp"
#include "smb/query.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

constexpr BoxId kTop = std::numeric_limits<BoxId>::max();
constexpr BoxId kTwo32 = BoxId{1} << 32;
constexpr BoxId kTwo63 = BoxId{1} << 63;

/// The edge ids, then ids that differ from them only in high bits, then random ones: `count`
/// distinct ids in all.
std::vector<BoxId> wide_ids(Random& random, std::size_t count) {
    std::vector<BoxId> ids = {0,
                              1,
                              7,
                              (BoxId{1} << 31) - 1,
                              BoxId{1} << 31,
                              kTwo32 - 1,
                              kTwo32,
                              kTwo32 + 1,
                              kTwo32 + 7,
                              (BoxId{1} << 53) + 1,
                              kTwo63 - 1,
                              kTwo63,
                              kTwo63 + 1,
                              kTwo63 + 7,
                              kTop - 1,
                              kTop,
                              kTop - kTwo32};
    std::set<BoxId> seen(ids.begin(), ids.end());
    while (ids.size() < count) {
        const BoxId id = random();
        // Every other one shares its low 32 bits with an id already drawn.
        const BoxId twin = chance(random, 0.5) ? (id & ~(kTwo32 - 1)) | (ids[ids.size() / 2] & (kTwo32 - 1)) : id;
        if (seen.insert(twin).second) ids.push_back(twin);
    }
    ids.resize(count);
    return ids;
}

/// The world's boxes by id, and what a test changes on it.
template <class World>
struct Scene {
    using box_type = typename World::box_type;
    std::map<BoxId, box_type> boxes;
    std::map<BoxId, Filter> filters;
    std::set<BoxId> statics;

    [[nodiscard]] std::vector<BoxId> ids() const {
        std::vector<BoxId> out;
        for (const auto& entry : boxes) out.push_back(entry.first);
        return out;
    }
    [[nodiscard]] std::vector<box_type> box_list() const {
        std::vector<box_type> out;
        for (const auto& entry : boxes) out.push_back(entry.second);
        return out;
    }
    [[nodiscard]] std::vector<Pair> pairs(bool filtered) const {
        const std::vector<BoxId> names = ids();
        const std::vector<box_type> list = box_list();
        std::vector<Pair> all = brute_force_pairs<typename World::real_type, World::dimension>(names, list);
        if (!filtered) return all;
        std::erase_if(all, [&](const Pair& p) {
            if (statics.contains(p.a) && statics.contains(p.b)) return true;
            if (!filters_pass(filter(p.a), filter(p.b))) return true;
            return !keep(p.a, p.b);
        });
        return all;
    }
    [[nodiscard]] Filter filter(BoxId id) const {
        const auto it = filters.find(id);
        return it == filters.end() ? Filter{} : it->second;
    }
    /// The predicate the filtered tests set: keeps a pair unless its ids agree in bits 32 and 63.
    static bool keep(BoxId a, BoxId b) { return ((a ^ b) & (kTwo32 | kTwo63)) != 0 || ((a ^ b) & 1) != 0; }
};

/// One step of churn: moves, teleports, removals and insertions (of ids from `spare`).
template <class World>
void churn(Random& random, World& world, Scene<World>& scene, std::vector<BoxId>& spare, double side) {
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    std::vector<BoxId> present = scene.ids();
    for (const BoxId id : present) {
        const double roll = uniform(random, 0, 1);
        if (roll < 0.5) {
            const auto box = perturbed<Real, Dim>(random, scene.boxes[id], 0.3, 0.05);
            world.update(id, box);
            scene.boxes[id] = box;
        } else if (roll < 0.55) {
            const auto box = particle_box<Real, Dim>(random, side, 0.3, 2.5);
            world.update(id, box);
            scene.boxes[id] = box;
        } else if (roll < 0.6) {
            world.remove(id);
            scene.boxes.erase(id);
            scene.filters.erase(id);
            scene.statics.erase(id);
            spare.push_back(id);
        }
    }
    const std::size_t fresh = std::min<std::size_t>(spare.size(), 1 + uniform_index(random, 6));
    for (std::size_t i = 0; i < fresh; ++i) {
        const std::size_t at = uniform_index(random, spare.size());
        const BoxId id = spare[at];
        spare.erase(spare.begin() + static_cast<std::ptrdiff_t>(at));
        const auto box = particle_box<Real, Dim>(random, side, 0.3, 2.5);
        world.insert(id, box);
        scene.boxes[id] = box;
    }
}

/// A world that holds `count` of `ids` (the rest spare) in a cube of `side`.
template <class World>
void fill(Random& random, World& world, Scene<World>& scene, std::vector<BoxId>& ids, std::size_t count, double side) {
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    for (std::size_t i = 0; i < count && !ids.empty(); ++i) {
        const BoxId id = ids.back();
        ids.pop_back();
        const auto box = particle_box<Real, Dim>(random, side, 0.3, 2.5);
        world.insert(id, box);
        scene.boxes[id] = box;
    }
}

/// A world holding `count` boxes under wide ids in a cube of `side`, what it should hold, and the
/// ids spare for arrivals; churn() changes both as a step of a test does.
template <class World>
struct WideWorld {
    WideWorld(std::uint64_t seed, double cube_side, std::size_t count, std::size_t id_count)
        : random(seed), side(cube_side), spare(wide_ids(random, id_count)) {
        fill(random, world, scene, spare, count, side);
    }
    void churn() { smb::test::churn(random, world, scene, spare, side); }

    Random random;
    double side;
    std::vector<BoxId> spare;
    World world;
    Scene<World> scene;
};

template <class T>
class WideIdsTest : public ::testing::Test {};

using WideIdWorlds = ::testing::Types<World2d, World3f>;
TYPED_TEST_SUITE(WideIdsTest, WideIdWorlds);

TYPED_TEST(WideIdsTest, PairsAndEventsOverManySteps) {
    using World = TypeParam;
    WideWorld<World> wide(35001, 14, 120, 160);
    PairEvents events;
    std::vector<Pair> before;
    std::vector<Pair> pairs;
    for (int step = 0; step < 40; ++step) {
        wide.world.detect(pairs, events);
        const std::vector<Pair> expected = wide.scene.pairs(false);
        ASSERT_TRUE(same_pairs(pairs, expected)) << "step " << step;
        // Events from the pairs before: every pair begun is present, every pair ended was, and
        // the pairs before less the ended plus the begun are the pairs now (a box removed and
        // inserted again may end and begin the same pair).
        std::vector<Pair> begun(events.begun().begin(), events.begun().end());
        std::vector<Pair> ended(events.ended().begin(), events.ended().end());
        std::sort(begun.begin(), begun.end());
        std::sort(ended.begin(), ended.end());
        ASSERT_TRUE(std::includes(expected.begin(), expected.end(), begun.begin(), begun.end())) << step;
        ASSERT_TRUE(std::includes(before.begin(), before.end(), ended.begin(), ended.end())) << step;
        std::vector<Pair> kept;
        std::set_difference(before.begin(), before.end(), ended.begin(), ended.end(), std::back_inserter(kept));
        std::vector<Pair> now;
        std::set_union(kept.begin(), kept.end(), begun.begin(), begun.end(), std::back_inserter(now));
        ASSERT_EQ(now, expected) << "step " << step;
        ASSERT_TRUE(std::adjacent_find(begun.begin(), begun.end()) == begun.end()) << step;
        ASSERT_TRUE(std::adjacent_find(ended.begin(), ended.end()) == ended.end()) << step;
        before = expected;
        for (const BoxId id : wide.scene.ids()) ASSERT_TRUE(wide.world.contains(id));
        wide.churn();
    }
}

TYPED_TEST(WideIdsTest, IdsPastThirtyTwoBitsArriveAndLeaveAWorldOfSmallIds) {
    // A world of small ids holds and carries them in 32 bits from one detection to the next; an
    // id past 2^32 (one sharing its low bits with a small id among them) makes it hold every id
    // whole, and its removal narrows them again. Each switch against brute force, with moves.
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    Random random(35006);
    const double side = 30;
    World world;
    Scene<World> scene;
    for (BoxId id = 0; id < 1500; ++id) {
        const auto box = particle_box<Real, Dim>(random, side, 0.3, 2.5);
        world.insert(id, box);
        scene.boxes[id] = box;
    }
    const std::vector<BoxId> wide = {kTwo32 + 3, kTop, kTwo63 + 700};
    std::vector<Pair> pairs;
    for (int step = 0; step < 24; ++step) {
        if (step % 8 == 3) {
            for (const BoxId id : wide) {
                // Near a small id's box (mostly over it), so that the wide ids are in pairs.
                const auto box = perturbed<Real, Dim>(random, scene.boxes[id & 1023], 0.3, 0.05);
                world.insert(id, box);
                scene.boxes[id] = box;
            }
        } else if (step % 8 == 6) {
            for (const BoxId id : wide) {
                world.remove(id);
                scene.boxes.erase(id);
            }
        }
        world.detect(pairs);
        ASSERT_TRUE(same_pairs(pairs, scene.pairs(false))) << "step " << step;
        for (auto& [id, box] : scene.boxes) {
            box = perturbed<Real, Dim>(random, box, 0.3, 0.05);
            world.update(id, box);
        }
    }
}

TYPED_TEST(WideIdsTest, PeriodicPairsOverManySteps) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    WideWorld<World> wide(35002, 12, 110, 150);
    const auto domain = cube_domain<Real, Dim>(wide.side, (1u << Dim) - 1);
    std::vector<PeriodicPair> pairs;
    PairEvents events;
    for (int step = 0; step < 40; ++step) {
        if (step % 2 == 0)
            wide.world.detect(domain, pairs);
        else
            wide.world.detect(domain, pairs, events);
        const std::vector<BoxId> ids = wide.scene.ids();
        const auto boxes = wide.scene.box_list();
        ASSERT_TRUE(same_periodic_pairs(pairs, brute_force_periodic_pairs<Real, Dim>(boxes, ids, domain)))
            << "step " << step;
        wide.churn();
    }
}

TYPED_TEST(WideIdsTest, TheIssuesThreeBoxes) {
    // 2^32 packed beside its index reached the bit that marks translated boxes: a crash with two
    // boxes, a pair dropped with a third.
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    const auto domain = cube_domain<Real, Dim>(12, (1u << Dim) - 1);
    auto box = [](double x0, double x1) {
        typename World::box_type b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = 0;
            b.max[k] = 1;
        }
        b.min[0] = static_cast<Real>(x0);
        b.max[0] = static_cast<Real>(x1);
        return b;
    };
    World world;
    world.insert(7, box(0, 1));
    world.insert(kTwo32, box(1, 2));
    std::vector<PeriodicPair> pairs;
    world.detect(domain, pairs);
    ASSERT_EQ(pairs, (std::vector<PeriodicPair>{{7, kTwo32, {0, 0, 0}}}));
    world.insert(kTop, box(11.5, 12));
    world.detect(domain, pairs);
    sort_periodic_pairs(pairs);
    ASSERT_EQ(pairs, (std::vector<PeriodicPair>{{7, kTwo32, {0, 0, 0}}, {7, kTop, {-1, 0, 0}}}));
}

TYPED_TEST(WideIdsTest, FiltersStaticsAndPredicateOverManySteps) {
    using World = TypeParam;
    WideWorld<World> wide(35003, 14, 120, 160);
    wide.world.set_pair_predicate(&Scene<World>::keep);
    std::vector<Pair> pairs;
    for (int step = 0; step < 40; ++step) {
        // Filters and static flags of a few boxes, one at a time and by span.
        std::vector<BoxId> ids;
        std::vector<Filter> filters;
        for (const BoxId id : wide.scene.ids()) {
            if (!chance(wide.random, 0.1)) continue;
            const Filter f{static_cast<std::uint32_t>(1 + uniform_index(wide.random, 3)),
                           static_cast<std::uint32_t>(uniform_index(wide.random, 8))};
            ids.push_back(id);
            filters.push_back(f);
            wide.scene.filters[id] = f;
            if (chance(wide.random, 0.3)) {
                const bool is_static = !wide.scene.statics.contains(id);
                wide.world.set_static(id, is_static);
                if (is_static)
                    wide.scene.statics.insert(id);
                else
                    wide.scene.statics.erase(id);
            }
        }
        wide.world.set_filter(ids, filters);
        for (const BoxId id : ids) ASSERT_EQ(wide.world.filter(id), wide.scene.filter(id));
        for (const BoxId id : wide.scene.ids())
            ASSERT_EQ(wide.world.is_static(id), wide.scene.statics.contains(id)) << id;
        wide.world.detect(pairs);
        ASSERT_TRUE(same_pairs(pairs, wide.scene.pairs(true))) << "step " << step;
        wide.churn();
    }
}

TYPED_TEST(WideIdsTest, QueriesAndRaysOverManySteps) {
    using World = TypeParam;
    using Real = typename World::real_type;
    constexpr int Dim = World::dimension;
    WideWorld<World> wide(35004, 14, 120, 160);
    std::vector<BoxId> found;
    std::vector<QueryHit> hits;
    std::vector<RayHit<Real>> ray_hits;
    for (int step = 0; step < 30; ++step) {
        std::vector<typename World::box_type> queries;
        for (int q = 0; q < 4; ++q) queries.push_back(particle_box<Real, Dim>(wide.random, wide.side, 0.5, 5));
        std::vector<QueryHit> expected_hits;
        for (std::size_t q = 0; q < queries.size(); ++q) {
            wide.world.query(queries[q], found);
            std::vector<BoxId> expected;
            for (const auto& [id, box] : wide.scene.boxes) {
                if (overlaps(box, queries[q])) {
                    expected.push_back(id);
                    expected_hits.push_back(QueryHit{q, id});
                }
            }
            std::sort(found.begin(), found.end());
            ASSERT_EQ(found, expected) << "step " << step;
        }
        wide.world.query(queries, hits);
        std::sort(hits.begin(), hits.end());
        ASSERT_EQ(hits, expected_hits) << "step " << step;

        Ray<Real, Dim> ray;
        for (int k = 0; k < Dim; ++k) {
            ray.origin[k] = static_cast<Real>(uniform(wide.random, -1, wide.side + 1));
            ray.direction[k] = static_cast<Real>(uniform(wide.random, -1, 1));
        }
        wide.world.cast_ray(ray, RayHits::all, ray_hits);
        std::vector<BoxId> entered;
        for (const auto& [id, box] : wide.scene.boxes) {
            if (ray_entry(ray, box)) entered.push_back(id);
        }
        std::vector<BoxId> hit_ids;
        for (const auto& h : ray_hits) hit_ids.push_back(h.id);
        std::sort(hit_ids.begin(), hit_ids.end());
        ASSERT_EQ(hit_ids, entered) << "step " << step;
        wide.churn();
    }
}

TEST(WideIdsPairEvents, NamesAcrossTheRangeBeginEndAndAreReplaced) {
    Random random(35005);
    std::vector<BoxId> names = wide_ids(random, 64);
    std::sort(names.begin(), names.end());
    std::set<Pair> live;
    PairEvents events;
    for (int step = 0; step < 60; ++step) {
        std::set<Pair> next;
        for (int i = 0; i < 80; ++i) {
            const std::size_t x = uniform_index(random, names.size());
            const std::size_t y = uniform_index(random, names.size());
            if (x != y) next.insert(Pair{names[std::min(x, y)], names[std::max(x, y)]});
        }
        // A replaced name ends its pairs and begins them again.
        std::optional<BoxId> replaced;
        if (chance(random, 0.3)) {
            replaced = names[uniform_index(random, names.size())];
            events.replace(*replaced);
        }
        const std::vector<Pair> now(next.begin(), next.end());
        events.update(now);
        std::set<Pair> want_begun;
        std::set<Pair> want_ended;
        for (const Pair& p : now) {
            const bool renewed = replaced && (p.a == *replaced || p.b == *replaced);
            if (!live.contains(p) || renewed) want_begun.insert(p);
        }
        for (const Pair& p : live) {
            const bool renewed = replaced && (p.a == *replaced || p.b == *replaced);
            if (!next.contains(p) || renewed) want_ended.insert(p);
        }
        ASSERT_EQ(std::set<Pair>(events.begun().begin(), events.begun().end()), want_begun) << "step " << step;
        ASSERT_EQ(std::set<Pair>(events.ended().begin(), events.ended().end()), want_ended) << "step " << step;
        live = next;
    }
}

TEST(WideIdsPairEvents, SwapRemoveRenamesWideNames) {
    PairEvents events;
    const std::vector<Pair> first = {{5, kTwo32}, {5, kTop}, {kTwo32 - 1, kTop}};
    events.update(first);
    // The body at 2^32 is gone; the body at 2^64 - 1 moved there: its pairs go on under the
    // new name, and the removed body's pairs end.
    events.swap_remove(kTwo32, kTop);
    const std::vector<Pair> second = {{5, kTwo32}, {kTwo32 - 1, kTwo32}};
    events.update(second);
    EXPECT_TRUE(events.begun().empty());
    ASSERT_EQ(events.ended().size(), 1u);
    EXPECT_EQ(events.ended()[0], (Pair{5, kTwo32}));
}

}  // namespace
}  // namespace smb::test
