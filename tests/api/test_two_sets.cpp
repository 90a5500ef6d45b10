// SPDX-License-Identifier: MIT
// The two-set find_overlapping_pairs (smb/join.hpp): pairs (index in the first set, index in the
// second) exactly as brute force over every cross pair finds them, sorted by (a, b).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "join/set_cull.hpp"
#include "reference/random_boxes.hpp"
#include "reference/world_types.hpp"
#include "smb/join.hpp"

namespace smb::test {
namespace {

template <std::floating_point Real, int Dim>
std::vector<Pair> brute_force_cross_pairs(const std::vector<Box<Real, Dim>>& first,
                                          const std::vector<Box<Real, Dim>>& second) {
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < first.size(); ++i) {
        for (std::size_t j = 0; j < second.size(); ++j) {
            if (overlaps(first[i], second[j])) pairs.push_back({i, j});
        }
    }
    return pairs;  // (i, j) order already
}

::testing::AssertionResult same_list(const std::vector<Pair>& reported, const std::vector<Pair>& expected) {
    if (reported == expected) return ::testing::AssertionSuccess();
    std::ostringstream out;
    out << "reported " << reported.size() << " pairs, expected " << expected.size();
    for (std::size_t i = 0; i < std::max(reported.size(), expected.size()); ++i) {
        const bool have = i < reported.size();
        const bool want = i < expected.size();
        if (have && want && reported[i] == expected[i]) continue;
        out << "; first difference at " << i << ": reported ";
        out << (have ? "(" + std::to_string(reported[i].a) + ", " + std::to_string(reported[i].b) + ")" : "nothing");
        out << ", expected ";
        out << (want ? "(" + std::to_string(expected[i].a) + ", " + std::to_string(expected[i].b) + ")" : "nothing");
        break;
    }
    return ::testing::AssertionFailure() << out.str();
}

template <typename WorldType>
class TwoSetsTest : public ::testing::Test {
protected:
    using Real = typename WorldType::real_type;
    static constexpr int Dim = WorldType::dimension;
    using BoxT = Box<Real, Dim>;
    using Boxes = std::vector<BoxT>;

    static ::testing::AssertionResult finds_like_brute_force(const Boxes& first, const Boxes& second,
                                                             const WorldSettings& settings = test_settings()) {
        const auto pairs = find_overlapping_pairs(first, second, settings);
        return same_list(pairs, brute_force_cross_pairs(first, second));
    }

    static Boxes random_boxes(std::uint64_t seed, std::size_t count, double lo, double hi, double min_side,
                              double max_side) {
        Random random(seed);
        Boxes boxes;
        for (std::size_t i = 0; i < count; ++i)
            boxes.push_back(random_box<Real, Dim>(random, lo, hi, min_side, max_side));
        return boxes;
    }

    /// A box from `lo` to `hi` on every axis but the last, and `bottom`..`top` on the last.
    static BoxT slab(double lo, double hi, double bottom, double top) {
        BoxT box;
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = static_cast<Real>(k == Dim - 1 ? bottom : lo);
            box.max[k] = static_cast<Real>(k == Dim - 1 ? top : hi);
        }
        return box;
    }
};

TYPED_TEST_SUITE(TwoSetsTest, WorldTypes, WorldTypeNames);

TYPED_TEST(TwoSetsTest, RandomSetsOfSeveralDensitiesAndBalances) {
    std::uint64_t seed = 700;
    for (const double space : {6.0, 20.0, 80.0}) {
        for (const auto& [count_first, count_second] :
             {std::array<std::size_t, 2>{800, 800}, {1500, 40}, {40, 1500}, {1, 900}}) {
            SCOPED_TRACE(::testing::Message() << "space " << space << ", " << count_first << " x " << count_second);
            const auto first = this->random_boxes(seed++, scaled(count_first), 0, space, 0.2, 2.0);
            const auto second = this->random_boxes(seed++, scaled(count_second), 0, space, 0.1, 3.0);
            EXPECT_TRUE(this->finds_like_brute_force(first, second));
        }
    }
}

TYPED_TEST(TwoSetsTest, EmptySets) {
    const typename TestFixture::Boxes none;
    const auto some = this->random_boxes(710, 50, 0, 5, 0.5, 1.0);
    EXPECT_TRUE(find_overlapping_pairs(none, none).empty());
    EXPECT_TRUE(find_overlapping_pairs(none, some).empty());
    EXPECT_TRUE(find_overlapping_pairs(some, none).empty());
}

// The indices are per set: the same boxes in both sets pair every box with its twin, (i, i),
// and a pair (a, b) may have a > b.
TYPED_TEST(TwoSetsTest, SameBoxesInBothSetsAndIdenticalBoxes) {
    const auto boxes = this->random_boxes(720, 300, 0, 12, 0.3, 1.5);
    const auto pairs = find_overlapping_pairs(boxes, boxes);
    EXPECT_TRUE(same_list(pairs, brute_force_cross_pairs(boxes, boxes)));
    for (std::size_t i = 0; i < boxes.size(); ++i)
        EXPECT_TRUE(std::binary_search(pairs.begin(), pairs.end(), Pair{i, i})) << i;

    const typename TestFixture::Boxes stack(60, this->slab(0, 1, 0, 1));  // 60 identical boxes
    const typename TestFixture::Boxes other(25, this->slab(0, 1, 0, 1));
    EXPECT_EQ(find_overlapping_pairs(stack, other).size(), 60u * 25u);
    EXPECT_TRUE(this->finds_like_brute_force(stack, other));
}

// Touching counts, on every axis; one float apart does not.
TYPED_TEST(TwoSetsTest, TouchingBoxesOverlap) {
    using R = typename TestFixture::Real;
    constexpr int dim = TestFixture::Dim;
    typename TestFixture::Boxes first;
    typename TestFixture::Boxes second;
    for (int k = 0; k < dim; ++k) {
        typename TestFixture::BoxT a;
        typename TestFixture::BoxT touching;
        typename TestFixture::BoxT apart;
        for (int j = 0; j < dim; ++j) {
            const auto base = static_cast<R>(10 * k);
            a.min[j] = base;
            a.max[j] = base + 1;
            touching.min[j] = j == k ? base + 1 : base;
            touching.max[j] = j == k ? base + 2 : base + 1;
            apart.min[j] = j == k ? std::nextafter(base + 1, R(100)) : base;
            apart.max[j] = j == k ? base + 3 : base + 1;
        }
        first.push_back(a);
        second.push_back(touching);
        second.push_back(apart);
    }
    const auto pairs = find_overlapping_pairs(first, second);
    EXPECT_TRUE(this->finds_like_brute_force(first, second));
    ASSERT_EQ(pairs.size(), static_cast<std::size_t>(dim));
    for (std::size_t k = 0; k < pairs.size(); ++k) EXPECT_EQ(pairs[k], (Pair{k, 2 * k}));
}

// Particles against a floor of zero thickness (some resting exactly on it) and against the
// walls of a container: the cases where most particles are left out before the detection.
TYPED_TEST(TwoSetsTest, ParticlesAgainstFloorAndWalls) {
    const auto particles = this->random_boxes(730, scaled(3000), 0.5, 19.5, 0.2, 1.0);
    typename TestFixture::Boxes floor;
    for (int i = 0; i < 20; ++i) floor.push_back(this->slab(i, i + 1, 0, 0));
    auto resting = particles;
    for (std::size_t i = 0; i < resting.size(); i += 7) {
        const auto height = resting[i].max[TestFixture::Dim - 1] - resting[i].min[TestFixture::Dim - 1];
        resting[i].min[TestFixture::Dim - 1] = 0;
        resting[i].max[TestFixture::Dim - 1] = height;
    }
    EXPECT_TRUE(this->finds_like_brute_force(resting, floor));
    EXPECT_TRUE(this->finds_like_brute_force(floor, resting));

    typename TestFixture::Boxes walls;  // thin panels on the six (four) sides of [0, 20]
    for (int k = 0; k < TestFixture::Dim; ++k) {
        for (const double side : {0.0, 20.0}) {
            for (int panel = 0; panel < 10; ++panel) {
                typename TestFixture::BoxT box;
                for (int j = 0; j < TestFixture::Dim; ++j) {
                    const bool along = j == (k + 1) % TestFixture::Dim;
                    box.min[j] = static_cast<typename TestFixture::Real>(j == k ? side - 0.1 : along ? 2 * panel : 0);
                    box.max[j] = static_cast<typename TestFixture::Real>(j == k  ? side + 0.1
                                                                         : along ? 2 * panel + 2
                                                                                 : 20);
                }
                walls.push_back(box);
            }
        }
    }
    EXPECT_TRUE(this->finds_like_brute_force(particles, walls));
    EXPECT_TRUE(this->finds_like_brute_force(resting, walls));
}

// Boxes that cover the whole scene, in the smaller set and in the larger one.
TYPED_TEST(TwoSetsTest, HugeBoxesAmongSmallOnes) {
    auto small = this->random_boxes(740, scaled(1200), 0, 50, 0.1, 1.0);
    auto few = this->random_boxes(741, 30, 0, 50, 0.1, 4.0);
    few[3] = this->slab(-10, 60, -10, 60);
    small[500] = this->slab(10, 40, -5, 55);
    EXPECT_TRUE(this->finds_like_brute_force(small, few));
    EXPECT_TRUE(this->finds_like_brute_force(few, small));
}

TYPED_TEST(TwoSetsTest, DisjointRegionsGiveNoPairs) {
    const auto left = this->random_boxes(750, 200, 0, 10, 0.5, 1.0);
    const auto right = this->random_boxes(751, 200, 100, 110, 0.5, 1.0);
    EXPECT_TRUE(find_overlapping_pairs(left, right).empty());
}

TYPED_TEST(TwoSetsTest, SettingsAndPipelinesDoNotChangeTheAnswer) {
    const auto first = this->random_boxes(760, scaled(600), 0, 15, 0.3, 2.0);
    const auto second = this->random_boxes(761, scaled(400), 0, 15, 0.3, 2.0);
    const auto expected = brute_force_cross_pairs(first, second);
    for (const Pipeline pipeline : {Pipeline::persistent_cuts, Pipeline::paper_lists}) {
        for (const std::size_t population : {std::size_t{1}, std::size_t{24}, std::size_t{100000}}) {
            SCOPED_TRACE(::testing::Message() << "population " << population);
            WorldSettings settings;
            settings.pipeline = pipeline;
            settings.target_cell_population = population;
            settings.pair_chunk_size = 1;
            settings.threads = population == 24 ? 2 : 1;  // the pairs do not depend on threads
            EXPECT_TRUE(same_list(find_overlapping_pairs(first, second, settings), expected));
        }
    }
}

TYPED_TEST(TwoSetsTest, TakesEveryContiguousRangeOfBoxes) {
    using B = typename TestFixture::BoxT;
    const auto first = this->random_boxes(770, 100, 0, 8, 0.3, 2.0);
    const std::array<B, 3> second{this->slab(0, 4, 0, 4), this->slab(4, 8, 4, 8), this->slab(20, 30, 20, 30)};
    const auto expected = brute_force_cross_pairs(first, std::vector<B>(second.begin(), second.end()));
    EXPECT_TRUE(same_list(find_overlapping_pairs(first, second), expected));
    EXPECT_TRUE(same_list(find_overlapping_pairs(std::span(first), std::span(second)), expected));
    EXPECT_TRUE(same_list(find_overlapping_pairs<typename TestFixture::Real, TestFixture::Dim>(
                              std::span<const B>(first), std::span<const B>(second)),
                          expected));
}

TYPED_TEST(TwoSetsTest, InvalidBoxNamesItsSetAndIndex) {
    using R = typename TestFixture::Real;
    auto first = this->random_boxes(780, 10, 0, 5, 0.5, 1.0);
    auto second = this->random_boxes(781, 10, 0, 5, 0.5, 1.0);
    second[7].min[0] = std::numeric_limits<R>::quiet_NaN();
    try {
        (void)find_overlapping_pairs(first, second);
        FAIL() << "no exception";
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("second set, box 7 is invalid"), std::string::npos) << error.what();
    }
    second[7] = first[0];
    first[2].max[1] = first[2].min[1] - 1;
    try {
        (void)find_overlapping_pairs(first, second);
        FAIL() << "no exception";
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("first set, box 2 is invalid"), std::string::npos) << error.what();
    }
}

TYPED_TEST(TwoSetsTest, PairLimit) {
    const typename TestFixture::Boxes stack(40, this->slab(0, 1, 0, 1));
    WorldSettings settings;
    settings.max_pairs_held = 1599;
    EXPECT_THROW((void)find_overlapping_pairs(stack, stack, settings), PairLimitError);
    settings.max_pairs_held = 1600;
    EXPECT_EQ(find_overlapping_pairs(stack, stack, settings).size(), 1600u);
}

// Far from the origin, with gaps a double resolves and a float would not.
TEST(TwoSets, DoublesFarFromTheOriginAreExact) {
    std::vector<Box3d> first;
    std::vector<Box3d> second;
    const double base = 1e9;
    for (int i = 0; i < 200; ++i) {
        const double x = base + i;
        first.push_back({{x, base, base}, {x + 0.5, base + 1, base + 1}});
        second.push_back({{x + 0.5 + (i % 2 == 0 ? 0.0 : 1e-6), base, base}, {x + 0.9, base + 1, base + 1}});
    }
    const auto pairs = find_overlapping_pairs(first, second);
    EXPECT_TRUE(same_list(pairs, brute_force_cross_pairs(first, second)));
    EXPECT_EQ(pairs.size(), 100u);
}

// What the cull before the detection leaves out: the particles far from a floor or from the
// walls, nothing where two sets are mixed evenly (src/join/set_cull.hpp).
TEST(TwoSetsCull, LeavesOutOnlyBoxesThatCannotMeetTheOtherSet) {
    Random random(790);
    std::vector<Box3d> particles;
    for (int i = 0; i < 8000; ++i) particles.push_back(random_box<double, 3>(random, 0.5, 29.5, 0.2, 1.0));
    std::vector<Box3d> floor;
    std::vector<Box3d> walls;
    for (int i = 0; i < 30; ++i) {
        for (int j = 0; j < 30; ++j) {
            const double x = i;
            const double y = j;
            floor.push_back({{x, y, 0.3}, {x + 1, y + 1, 0.3}});
            walls.push_back({{-0.1, x, y}, {0.1, x + 1, y + 1}});
            walls.push_back({{29.9, x, y}, {30.1, x + 1, y + 1}});
        }
    }
    // Every box left out overlaps no box of the other set.
    auto expect_left_out_meet_nothing = [](const std::vector<Box3d>& boxes, const std::vector<std::size_t>& kept,
                                           const std::vector<Box3d>& others) {
        std::size_t next = 0;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (next < kept.size() && kept[next] == i) {
                ++next;
                continue;
            }
            for (const Box3d& other : others) ASSERT_FALSE(overlaps(boxes[i], other)) << i;
        }
    };
    const auto on_floor = detail::SetCull<double, 3>::keep(particles, floor);
    EXPECT_LT(on_floor.first.size(), particles.size() / 20);  // the region: a thin slab
    expect_left_out_meet_nothing(particles, on_floor.first, floor);
    expect_left_out_meet_nothing(floor, on_floor.second, particles);
    const auto on_walls = detail::SetCull<double, 3>::keep(particles, walls);
    EXPECT_LT(on_walls.first.size(), particles.size() / 5);  // the grid: two walls of a cube
    expect_left_out_meet_nothing(particles, on_walls.first, walls);
    expect_left_out_meet_nothing(walls, on_walls.second, particles);

    // Two dense sets over the same cube: every box may meet the other set.
    std::vector<Box3d> dense;
    std::vector<Box3d> mixed;
    for (int i = 0; i < 20000; ++i) dense.push_back(random_box<double, 3>(random, 0, 15, 0.2, 1.0));
    for (int i = 0; i < 20000; ++i) mixed.push_back(random_box<double, 3>(random, 0, 15, 0.2, 1.0));
    const auto even = detail::SetCull<double, 3>::keep(dense, mixed);
    EXPECT_EQ(even.first.size(), dense.size());
    EXPECT_EQ(even.second.size(), mixed.size());
}

}  // namespace
}  // namespace smb::test
