// SPDX-License-Identifier: MIT
// Seeded random scenes driven incrementally over dozens of steps (motion, deformation,
// insertion, deletion, through single calls, batch calls and assign), every detection
// compared pair for pair with brute force.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reference/random_boxes.hpp"
#include "reference/reference_world.hpp"
#include "reference/world_types.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

/// One kind of scene. Sizes are side lengths; the space side follows from the density
/// (the paper's E: total box volume over space volume), so a regime means the same in 2D and 3D.
struct Regime {
    std::size_t count = 500;
    double min_side = 1.0;
    double max_side = 2.0;
    double density = 0.3;
    double large_fraction = 0.0;  ///< share of boxes with a side of large_side_ratio * space
    double large_side_ratio = 0.0;
    double motion = 1e-3;        ///< the paper's update factor: shift up to motion * space
    double churn = 0.02;         ///< share of boxes removed and inserted each step
    double jump_chance = 0.002;  ///< per box and step: teleport anywhere in the space
    int steps = 30;
};

template <typename WorldType>
class WorldRandomTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;

    /// Runs one regime from one seed; returns a fingerprint of every detection's raw output
    /// (its pairs in reported order), so that determinism can be checked by running twice.
    std::uint64_t run(const Regime& regime, std::uint64_t seed, const WorldSettings& settings = test_settings()) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Random random(seed);
        const double mean_side = 0.5 * (regime.min_side + regime.max_side);
        space_ = std::pow(static_cast<double>(regime.count) * std::pow(mean_side, Dim) / regime.density, 1.0 / Dim);
        regime_ = regime;

        World<Real, Dim> world(settings);
        ReferenceWorld<Real, Dim> reference;
        next_id_ = 0;
        std::vector<BoxId> ids;
        std::vector<BoxT> boxes;
        for (std::size_t i = 0; i < regime.count; ++i) {
            ids.push_back(fresh_id(random));
            boxes.push_back(new_box(random));
        }
        world.insert(ids, boxes);
        for (std::size_t i = 0; i < ids.size(); ++i) reference.insert(ids[i], boxes[i]);

        std::uint64_t fingerprint = 1469598103934665603ull;
        for (int step = 0; step < regime.steps; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            if (step > 0) advance(random, step, world, reference);
            std::vector<Pair> pairs;
            const DetectStats stats = world.detect(pairs);
            EXPECT_EQ(stats.pairs, pairs.size());
            EXPECT_EQ(stats.boxes, reference.size());
            EXPECT_TRUE(same_pairs(pairs, reference.pairs(), reference.describer()));
            for (const Pair& p : pairs) fingerprint = (fingerprint ^ p.a ^ (p.b << 1)) * 1099511628211ull;
            if (::testing::Test::HasFailure()) break;
        }
        EXPECT_TRUE(same_contents(world, reference));
        return fingerprint;
    }

private:
    BoxId fresh_id(Random& random) {
        // Gaps between ids, so that ids are not slots in disguise; some far above the others, so
        // that the id index keeps both its array (small ids) and its hash map (large ones) busy.
        next_id_ += 1 + uniform_index(random, 3);
        if (chance(random, 0.1)) return next_id_ | (BoxId{1} << 40) | (BoxId{uniform_index(random, 1000)} << 50);
        return next_id_;
    }

    BoxT new_box(Random& random) const {
        if (chance(random, regime_.large_fraction)) {
            const double side = regime_.large_side_ratio * space_;
            return random_box<Real, Dim>(random, 0.0, space_, 0.5 * side, side);
        }
        return random_box<Real, Dim>(random, 0.0, space_, regime_.min_side, regime_.max_side);
    }

    BoxT moved(Random& random, const BoxT& box) const {
        if (chance(random, regime_.jump_chance)) return new_box(random);
        return perturbed(random, box, regime_.motion * space_, regime_.motion * regime_.max_side);
    }

    /// One step of the scene. The way each change reaches the world varies with the step, so
    /// that every entry point is used with pending changes of every other kind.
    void advance(Random& random, int step, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        if (step % 10 == 5) {
            assign_all(random, world, reference);
            return;
        }
        move_boxes(random, step, world, reference);
        remove_some(random, step, world, reference);
        insert_some(random, step, world, reference);
        if (step % 7 == 3) reinsert_some(random, world, reference);
    }

    void move_boxes(Random& random, int step, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        // Every box moves on most steps; on every third step only about half do.
        const double share = step % 3 == 2 ? 0.5 : 1.0;
        std::vector<BoxId> ids;
        std::vector<BoxT> boxes;
        for (const auto& [id, box] : reference.boxes()) {
            if (share < 1.0 && !chance(random, share)) continue;
            ids.push_back(id);
            boxes.push_back(moved(random, box));
        }
        if (step % 2 == 0) {
            world.update(ids, boxes);
        } else {
            for (std::size_t i = 0; i < ids.size(); ++i) world.update(ids[i], boxes[i]);
        }
        for (std::size_t i = 0; i < ids.size(); ++i) reference.update(ids[i], boxes[i]);
    }

    std::size_t churn_count(Random& random) const {
        const double expected = regime_.churn * static_cast<double>(regime_.count);
        return static_cast<std::size_t>(uniform(random, 0.0, 2.0 * expected) + 0.5);
    }

    void remove_some(Random& random, int step, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        std::vector<BoxId> present = reference.ids();
        std::vector<BoxId> doomed;
        const std::size_t count = std::min(churn_count(random), present.size());
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t pick = i + uniform_index(random, present.size() - i);
            std::swap(present[i], present[pick]);
            doomed.push_back(present[i]);
        }
        if (step % 2 == 1) {
            world.remove(doomed);
        } else {
            for (const BoxId id : doomed) world.remove(id);
        }
        for (const BoxId id : doomed) reference.remove(id);
    }

    void insert_some(Random& random, int step, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        // Grow back towards the regime's count, with some noise either way.
        const std::size_t deficit = reference.size() < regime_.count ? regime_.count - reference.size() : 0;
        const std::size_t count = deficit / 2 + churn_count(random);
        std::vector<BoxId> ids;
        std::vector<BoxT> boxes;
        for (std::size_t i = 0; i < count; ++i) {
            ids.push_back(fresh_id(random));
            boxes.push_back(new_box(random));
        }
        if (step % 3 != 0) {
            world.insert(ids, boxes);
        } else {
            for (std::size_t i = 0; i < ids.size(); ++i) world.insert(ids[i], boxes[i]);
        }
        for (std::size_t i = 0; i < ids.size(); ++i) reference.insert(ids[i], boxes[i]);
    }

    /// Removes a few boxes and inserts them again under the same id before the next
    /// detection: half at the same place, half elsewhere.
    void reinsert_some(Random& random, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        const std::vector<BoxId> present = reference.ids();
        if (present.empty()) return;
        for (int i = 0; i < 4; ++i) {
            const BoxId id = present[uniform_index(random, present.size())];
            if (!reference.contains(id)) continue;
            const BoxT box = i % 2 == 0 ? reference.box(id) : new_box(random);
            world.remove(id);
            reference.remove(id);
            world.insert(id, box);
            reference.insert(id, box);
        }
    }

    /// Renumbers the scene as an array-based simulation would: the current boxes, moved, as
    /// ids 0..n-1 (a size that wanders a little), everything else removed.
    void assign_all(Random& random, World<Real, Dim>& world, ReferenceWorld<Real, Dim>& reference) {
        std::vector<BoxT> boxes;
        for (const auto& entry : reference.boxes()) boxes.push_back(moved(random, entry.second));
        const std::size_t extra = churn_count(random);
        for (std::size_t i = 0; i < extra; ++i) boxes.push_back(new_box(random));
        const std::size_t dropped = std::min(churn_count(random), boxes.size());
        boxes.resize(boxes.size() - dropped);
        world.assign(boxes);
        reference.assign(boxes);
        next_id_ = boxes.size();
    }

    Regime regime_;
    double space_ = 1.0;
    BoxId next_id_ = 0;
};

TYPED_TEST_SUITE(WorldRandomTest, WorldTypes, WorldTypeNames);

TYPED_TEST(WorldRandomTest, SparseSlowMotion) {
    Regime regime;
    regime.count = scaled(800);
    regime.density = 0.05;
    for (const std::uint64_t seed : {11u, 12u}) this->run(regime, seed);
}

TYPED_TEST(WorldRandomTest, DenseScene) {
    Regime regime;
    regime.count = scaled(800);
    regime.density = 0.45;
    regime.min_side = 0.5;
    regime.max_side = 1.5;
    for (const std::uint64_t seed : {21u, 22u}) this->run(regime, seed);
}

TYPED_TEST(WorldRandomTest, FewLargeBoxesAmongSmallOnes) {
    Regime regime;
    regime.count = scaled(800);
    regime.min_side = 0.1;
    regime.max_side = 1.0;
    regime.density = 0.1;
    regime.large_fraction = 0.02;
    regime.large_side_ratio = 0.4;
    for (const std::uint64_t seed : {31u, 32u}) this->run(regime, seed);
}

TYPED_TEST(WorldRandomTest, SizesOverFourOrdersOfMagnitude) {
    Regime regime;
    regime.count = scaled(600);
    regime.min_side = 1e-3;
    regime.max_side = 10.0;
    regime.density = 0.2;
    regime.large_fraction = 0.01;
    regime.large_side_ratio = 0.9;
    this->run(regime, 41);
}

TYPED_TEST(WorldRandomTest, FastMotionWeakCoherence) {
    Regime regime;
    regime.count = scaled(600);
    regime.density = 0.3;
    regime.motion = 0.05;
    regime.jump_chance = 0.05;
    this->run(regime, 51);
}

TYPED_TEST(WorldRandomTest, HeavyChurn) {
    Regime regime;
    regime.count = scaled(600);
    regime.density = 0.3;
    regime.churn = 0.25;
    this->run(regime, 61);
}

TYPED_TEST(WorldRandomTest, TinyWorldThatEmptiesAndRefills) {
    Regime regime;
    regime.count = 4;
    regime.density = 0.5;
    regime.churn = 0.5;
    regime.steps = 80;
    for (const std::uint64_t seed : {71u, 72u, 73u}) this->run(regime, seed);
}

TYPED_TEST(WorldRandomTest, ManyDetectionsInARow) {
    Regime regime;
    regime.count = scaled(300);
    regime.density = 0.3;
    regime.motion = 2e-4;
    regime.churn = 0.005;
    regime.steps = 150;
    this->run(regime, 81);
}

TYPED_TEST(WorldRandomTest, SmallAndLargeCellPopulations) {
    Regime regime;
    regime.count = scaled(500);
    regime.density = 0.3;
    regime.large_fraction = 0.01;
    regime.large_side_ratio = 0.5;
    regime.steps = 15;
    for (const std::size_t population : {std::size_t{1}, std::size_t{2}, std::size_t{7}, std::size_t{10000}}) {
        SCOPED_TRACE(::testing::Message() << "target_cell_population " << population);
        WorldSettings settings = test_settings();
        settings.target_cell_population = population;
        this->run(regime, 91, settings);
    }
}

TYPED_TEST(WorldRandomTest, SameCallsGiveSamePairsInSameOrder) {
    Regime regime;
    regime.count = scaled(400);
    regime.density = 0.3;
    regime.steps = 12;
    const std::uint64_t first = this->run(regime, 101);
    const std::uint64_t second = this->run(regime, 101);
    EXPECT_EQ(first, second);
}

TYPED_TEST(WorldRandomTest, SkinKeepsEveryRegimeExact) {
    if (test_pipeline() == Pipeline::paper_lists) GTEST_SKIP() << "the paper's lists keep no skin";
    // Moves, teleports, insertions, removals, reinsertions and assign() under a skin: one a
    // few steps of motion wide, one far wider, one thinner than a step (it steps aside).
    Regime sparse;
    sparse.count = scaled(600);
    sparse.density = 0.1;
    Regime churn = sparse;
    churn.churn = 0.25;
    Regime fast = sparse;
    fast.motion = 0.05;
    fast.jump_chance = 0.05;
    Regime tiny;
    tiny.count = 4;
    tiny.churn = 0.5;
    tiny.steps = 60;
    for (const double skin : {0.2, 2.0, 1e-4}) {
        SCOPED_TRACE(::testing::Message() << "skin " << skin);
        WorldSettings settings = test_settings();
        settings.skin = skin;
        for (const Regime& regime : {sparse, churn, fast, tiny}) this->run(regime, 121, settings);
        settings.threads = 3;
        this->run(sparse, 122, settings);
    }
}

TYPED_TEST(WorldRandomTest, ThreadCountChangesNeitherPairsNorOrder) {
    // Every detection is checked against brute force inside run(); the fingerprints then show
    // that the order of the report does not depend on the number of threads either. Large
    // boxes make some of them oversized, which the threads mark concurrently.
    Regime regime;
    regime.count = scaled(3000);
    regime.density = 0.3;
    regime.large_fraction = 0.01;
    regime.large_side_ratio = 0.3;
    regime.churn = 0.05;
    regime.steps = 10;
    WorldSettings settings = test_settings();
    settings.target_cell_population = 8;  // many groups and columns to share out
    settings.threads = 1;
    const std::uint64_t one = this->run(regime, 111, settings);
    for (const std::size_t threads : {std::size_t{2}, std::size_t{3}, std::size_t{0}}) {
        SCOPED_TRACE(::testing::Message() << "threads " << threads);
        settings.threads = threads;
        EXPECT_EQ(this->run(regime, 111, settings), one);
    }
}

}  // namespace
}  // namespace smb::test
