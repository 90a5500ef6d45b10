// SPDX-License-Identifier: MIT
// Detector's periodic detection against the brute force over the 3^D images: random scenes over
// many steps (motion across the boundary, boxes drifting away, teleports, growing and shrinking
// arrays), one and two threads, with and without the skin; boxes touching across the boundary,
// at lo and just below hi, far outside the domain; a domain one box wide; rejected input.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "reference/periodic_brute_force.hpp"
#include "reference/world_types.hpp"
#include "smb/detector.hpp"

namespace smb::test {
namespace {

template <class R, int D>
struct Kind {
    using Real = R;
    static constexpr int Dim = D;
};

template <class T>
class PeriodicDetectorTest : public ::testing::Test {};

using Kinds = ::testing::Types<Kind<float, 2>, Kind<double, 2>, Kind<float, 3>, Kind<double, 3>>;
TYPED_TEST_SUITE(PeriodicDetectorTest, Kinds);

template <std::floating_point Real, int Dim>
std::vector<PeriodicPair> brute(const std::vector<Box<Real, Dim>>& boxes, const PeriodicDomain<Real, Dim>& domain) {
    return brute_force_periodic_pairs<Real, Dim>(boxes, {}, domain);
}

TYPED_TEST(PeriodicDetectorTest, RandomScenesOverManyStepsMatchBruteForce) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    const double side = 20;
    const unsigned all = (1u << Dim) - 1;
    for (const unsigned axes : {all, 1u, all & ~1u}) {
        Random random(1000 + axes);
        const auto domain = cube_domain<Real, Dim>(side, axes);
        std::vector<Box<Real, Dim>> boxes;
        for (std::size_t i = 0; i < scaled(250); ++i)
            boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, Dim == 2 ? 2.5 : 4.0));
        DetectorSettings one;
        DetectorSettings two;
        two.threads = 2;
        two.target_cell_population = 6;  // more cells, so that two threads share the work
        DetectorSettings skin;
        skin.skin = 0.5;
        Detector<Real, Dim> detector(one);
        Detector<Real, Dim> threaded(two);
        Detector<Real, Dim> skinned(skin);
        std::vector<PeriodicPair> pairs;
        std::vector<PeriodicPair> pairs_threaded;
        std::vector<PeriodicPair> pairs_skinned;
        for (int step = 0; step < 12; ++step) {
            SCOPED_TRACE("axes " + std::to_string(axes) + ", step " + std::to_string(step));
            detector.detect(boxes, domain, pairs);
            threaded.detect(boxes, domain, pairs_threaded);
            skinned.detect(boxes, domain, pairs_skinned);
            const auto expected = brute(boxes, domain);
            ASSERT_TRUE(same_periodic_pairs(pairs, expected));
            ASSERT_TRUE(same_periodic_pairs(pairs_skinned, expected));
            // Two threads over other cells: the same pairs; one thread twice: the same order.
            ASSERT_TRUE(same_periodic_pairs(pairs_threaded, expected));
            EXPECT_EQ(detector.last_stats().pairs, expected.size());
            for (auto& box : boxes) box = moved(random, box, domain, 0.3, chance(random, 0.05));
            if (step % 6 == 3) {  // teleports, some several periods away
                for (int t = 0; t < 10; ++t) {
                    auto& box = boxes[uniform_index(random, boxes.size())];
                    box = translated(particle_box<Real, Dim>(random, side, 0.2, 2.0), domain,
                                     static_cast<int>(uniform_index(random, 7)) - 3);
                }
            }
            if (step % 4 == 1) boxes.resize(boxes.size() - boxes.size() / 8);  // shrink
            if (step % 4 == 2) {                                               // grow
                for (int g = 0; g < 40; ++g) boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, 2.0));
            }
        }
    }
}

TYPED_TEST(PeriodicDetectorTest, TheSkinKeepsCandidatesAcrossTheBoundary) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    Random random(31);
    const double side = 16;
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(400); ++i) boxes.push_back(particle_box<Real, Dim>(random, side, 0.3, 1.5));
    DetectorSettings settings;
    settings.skin = 0.3;
    Detector<Real, Dim> detector(settings);
    std::vector<PeriodicPair> pairs;
    std::size_t with_candidates = 0;
    for (int step = 0; step < 30; ++step) {
        detector.detect(boxes, domain, pairs);
        ASSERT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain))) << "step " << step;
        with_candidates += detector.last_stats().skin_candidates > 0 ? 1 : 0;
        // Small steps, the centres wrapped: boxes cross the boundary under the skin.
        for (auto& box : boxes) box = moved(random, box, domain, 0.03, false);
        if (step % 10 == 5) boxes.pop_back();
    }
    EXPECT_GT(with_candidates, 20u) << "the skin list did not detect";
}

TYPED_TEST(PeriodicDetectorTest, EmptyArrays) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    const auto domain = cube_domain<Real, Dim>(4, 1);
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs{PeriodicPair{1, 2, {}}};
    detector.detect(std::span<const Box<Real, Dim>>{}, domain, pairs);
    EXPECT_TRUE(pairs.empty());
    std::vector<Box<Real, Dim>> one(1);
    detector.detect(one, domain, pairs);
    EXPECT_TRUE(pairs.empty());
}

TYPED_TEST(PeriodicDetectorTest, ThreadCountGivesTheSamePairsInTheSameOrder) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    Random random(7);
    const double side = 30;
    const auto domain = cube_domain<Real, Dim>(side, (1u << Dim) - 1);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(3000); ++i) boxes.push_back(particle_box<Real, Dim>(random, side, 0.2, 2.0));
    DetectorSettings two;
    two.threads = 2;
    Detector<Real, Dim> single;
    Detector<Real, Dim> threaded(two);
    std::vector<PeriodicPair> a;
    std::vector<PeriodicPair> b;
    for (int step = 0; step < 5; ++step) {
        single.detect(boxes, domain, a);
        threaded.detect(boxes, domain, b);
        ASSERT_EQ(a, b) << "step " << step;
        for (auto& box : boxes) box = moved(random, box, domain, 0.2, false);
    }
}

TYPED_TEST(PeriodicDetectorTest, BoxesTouchingAcrossTheBoundary) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    PeriodicDomain<Real, Dim> domain;
    for (int k = 0; k < Dim; ++k) domain.wrap(k, Real(0), Real(10));
    auto box = [](Real x0, Real x1, Real y0, Real y1) {
        Box<Real, Dim> b;
        b.min[0] = x0;
        b.max[0] = x1;
        b.min[1] = y0;
        b.max[1] = y1;
        if constexpr (Dim == 3) {
            b.min[2] = 2;
            b.max[2] = 3;
        }
        return b;
    };
    const Real below_ten = std::nextafter(Real(10), Real(0));
    const std::vector<Box<Real, Dim>> boxes{
        box(0, 1, 2, 3),           // 0: at lo
        box(9, 10, 2, 3),          // 1: touches 0 across x (its max is hi)
        box(8, below_ten, 5, 6),   // 2: stops just short of hi: touches nothing across
        box(0, 1, 0, 1),           // 3: the corner at lo
        box(9, 10, 9, 10),         // 4: touches 3 at the corner across x and y
        box(10, 11, 2, 3),         // 5: box 0 one period away: touches 1 directly, 0 under +1
        box(-10, -9, 2, 3),        // 6: box 0 one period back
        box(-1, 0, 7, 8),          // 7: sticks out below lo
        box(below_ten, 10, 7, 8),  // 8: at the top of x, touches 7 under -1... and more
    };
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs;
    detector.detect(boxes, domain, pairs);
    const auto expected = brute(boxes, domain);
    ASSERT_TRUE(same_periodic_pairs(pairs, expected));
    auto has = [&](BoxId a, BoxId b, std::int32_t sx, std::int32_t sy) {
        return std::find(expected.begin(), expected.end(), PeriodicPair{a, b, {sx, sy, 0}}) != expected.end();
    };
    EXPECT_TRUE(has(0, 1, -1, 0));
    EXPECT_TRUE(has(3, 4, -1, -1));
    EXPECT_TRUE(has(0, 5, 1, 0) || has(0, 5, -1, 0));
    EXPECT_TRUE(has(1, 5, 0, 0));
    EXPECT_TRUE(has(0, 6, 1, 0));
    for (const auto& p : expected) EXPECT_FALSE(p.a == 0 && p.b == 2) << describe(p);
}

TYPED_TEST(PeriodicDetectorTest, BoxesAtLoJustBelowHiAndFarAway) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    const Real lo = Real(-3.5);
    const Real hi = Real(6.25);
    PeriodicDomain<Real, Dim> domain;
    for (int k = 0; k < Dim; ++k) domain.wrap(k, lo, hi);
    const Real inf = std::numeric_limits<Real>::infinity();
    const Real period = hi - lo;
    const std::vector<Real> mins{lo,
                                 std::nextafter(lo, inf),
                                 std::nextafter(lo, -inf),
                                 std::nextafter(hi, -inf),
                                 hi,
                                 std::nextafter(hi, inf),
                                 Real(lo - 1),
                                 Real(hi - 1),
                                 Real(lo + 3 * period),
                                 Real(hi - 5 * period),
                                 Real(lo + 1)};
    const std::vector<Real> extents{0, 1, Real(0.25), std::nextafter(Real(1), Real(0))};
    Random random(99);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(400); ++i) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = mins[uniform_index(random, mins.size())];
            b.max[k] = b.min[k] + extents[uniform_index(random, extents.size())];
        }
        boxes.push_back(b);
    }
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs;
    detector.detect(boxes, domain, pairs);
    EXPECT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain)));
}

TYPED_TEST(PeriodicDetectorTest, TranslatingBoxesByWholePeriodsOffsetsTheirShifts) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    // Coordinates on a grid of 1/64 within 16-periods: every translation is exact.
    const auto domain = cube_domain<Real, Dim>(16, (1u << Dim) - 1);
    Random random(5);
    std::vector<Box<Real, Dim>> boxes;
    std::vector<int> periods;
    for (std::size_t i = 0; i < scaled(300); ++i) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = Real(static_cast<double>(uniform_index(random, 16 * 64)) / 64);
            b.max[k] = b.min[k] + Real(static_cast<double>(uniform_index(random, 3 * 64)) / 64);
        }
        boxes.push_back(b);
        periods.push_back(static_cast<int>(uniform_index(random, 11)) - 5);
    }
    std::vector<Box<Real, Dim>> far;
    for (std::size_t i = 0; i < boxes.size(); ++i) far.push_back(translated(boxes[i], domain, periods[i]));
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> near_pairs;
    std::vector<PeriodicPair> far_pairs;
    detector.detect(boxes, domain, near_pairs);
    detector.detect(far, domain, far_pairs);
    EXPECT_TRUE(same_periodic_pairs(far_pairs, brute(far, domain)));
    // b's shift relative to a: s' = s + k_a - k_b.
    for (auto& p : near_pairs) {
        for (int k = 0; k < Dim; ++k) p.shift[k] += periods[p.a] - periods[p.b];
    }
    EXPECT_TRUE(same_periodic_pairs(far_pairs, near_pairs));
}

TYPED_TEST(PeriodicDetectorTest, DomainOneBoxWide) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    Random random(11);
    // The period just above twice the extents: every box is within reach of every other.
    const double extent = 1;
    const double period = 2 * extent * (1 + 1e-3);
    PeriodicDomain<Real, Dim> domain;
    domain.wrap(0, Real(0), Real(period));
    if constexpr (Dim == 3) domain.wrap(2, Real(-1), Real(-1 + period));
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(160); ++i) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            const double lo = domain.periodic[k] ? double(domain.lo[k]) : 0.0;
            const double span = domain.periodic[k] ? period : 30.0;
            b.min[k] = Real(lo + uniform(random, 0, span));
            b.max[k] = Real(double(b.min[k]) + (chance(random, 0.3) ? extent : uniform(random, 0, extent)));
        }
        boxes.push_back(b);
    }
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs;
    for (int step = 0; step < 4; ++step) {
        detector.detect(boxes, domain, pairs);
        ASSERT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain))) << "step " << step;
        for (auto& box : boxes) box = moved(random, box, domain, 0.3, false);
    }
}

TYPED_TEST(PeriodicDetectorTest, RejectedInputChangesNothing) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    const auto domain = cube_domain<Real, Dim>(10, (1u << Dim) - 1);
    Random random(3);
    std::vector<Box<Real, Dim>> boxes;
    for (int i = 0; i < 50; ++i) boxes.push_back(particle_box<Real, Dim>(random, 10, 0.5, 2));
    Detector<Real, Dim> detector;
    std::vector<PeriodicPair> pairs;
    detector.detect(boxes, domain, pairs);
    const auto before = pairs;

    auto too_large = boxes;
    too_large[17].min[0] = Real(1);
    too_large[17].max[0] = Real(6);  // exactly half the period
    EXPECT_THROW(detector.detect(too_large, domain, pairs), InvalidBoxError);
    try {
        detector.detect(too_large, domain, pairs);
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("box 17"), std::string::npos) << error.what();
    }
    auto not_a_number = boxes;
    not_a_number[3].min[1] = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(detector.detect(not_a_number, domain, pairs), InvalidBoxError);
    auto too_far = boxes;
    too_far[4].min[0] = Real(1e30);
    too_far[4].max[0] = Real(1e30);
    EXPECT_THROW(detector.detect(too_far, domain, pairs), InvalidBoxError);

    auto empty = domain;
    empty.hi[0] = empty.lo[0];
    EXPECT_THROW(detector.detect(boxes, empty, pairs), ArgumentError);
    auto reversed = domain;
    reversed.lo[0] = Real(11);
    EXPECT_THROW(detector.detect(boxes, reversed, pairs), ArgumentError);
    auto nan = domain;
    nan.lo[Dim - 1] = std::numeric_limits<Real>::quiet_NaN();
    EXPECT_THROW(detector.detect(boxes, nan, pairs), ArgumentError);
    auto infinite = domain;
    infinite.hi[0] = std::numeric_limits<Real>::infinity();
    EXPECT_THROW(detector.detect(boxes, infinite, pairs), ArgumentError);
    EXPECT_EQ(pairs, before);

    // An axis that is not periodic takes any extent.
    auto open = domain;
    open.periodic[0] = false;
    EXPECT_NO_THROW(detector.detect(too_large, open, pairs));
    EXPECT_TRUE(same_periodic_pairs(pairs, brute(too_large, open)));
    detector.detect(boxes, domain, pairs);
    EXPECT_TRUE(same_periodic_pairs(pairs, before));
}

TYPED_TEST(PeriodicDetectorTest, WithoutPeriodicAxesItIsTheOrdinaryDetection) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    Random random(21);
    std::vector<Box<Real, Dim>> boxes;
    for (std::size_t i = 0; i < scaled(800); ++i) boxes.push_back(particle_box<Real, Dim>(random, 15, 0.2, 30));
    Detector<Real, Dim> detector;
    std::vector<Pair> plain;
    std::vector<PeriodicPair> periodic;
    detector.detect(boxes, plain);
    detector.detect(boxes, PeriodicDomain<Real, Dim>{}, periodic);
    std::vector<PeriodicPair> expected;
    for (const Pair& p : plain) expected.push_back(PeriodicPair{p.a, p.b, {}});
    EXPECT_TRUE(same_periodic_pairs(periodic, expected));
}

TYPED_TEST(PeriodicDetectorTest, APairThatCrossesTheBoundaryStaysOneContact) {
    using Real = typename TypeParam::Real;
    constexpr int Dim = TypeParam::Dim;
    const auto domain = cube_domain<Real, Dim>(10, (1u << Dim) - 1);
    // Two unit boxes side by side travel along x through the boundary, wrapped as a DEM code
    // wraps its particles; a third one stays apart.
    auto at = [](double x, double y) {
        Box<Real, Dim> b;
        for (int k = 0; k < Dim; ++k) {
            b.min[k] = Real(k == 0 ? x : y);
            b.max[k] = Real((k == 0 ? x : y) + 1);
        }
        return b;
    };
    auto wrapped = [](double x) { return x >= 10 ? x - 10 : x; };
    Detector<Real, Dim> detector;
    PairEvents events;
    std::vector<PeriodicPair> pairs;
    std::vector<std::array<std::int32_t, 3>> shifts;
    for (int step = 0; step < 24; ++step) {
        const double x = 7 + 0.25 * step;
        const std::vector<Box<Real, Dim>> boxes{at(wrapped(x), 2), at(wrapped(x + 0.75), 2), at(5, 6)};
        detector.detect(boxes, domain, pairs, events);
        ASSERT_EQ(pairs.size(), 1u) << "step " << step;
        EXPECT_TRUE(same_periodic_pairs(pairs, brute(boxes, domain)));
        shifts.push_back(pairs[0].shift);
        if (step == 0) {
            EXPECT_EQ(events.begun().size(), 1u);
        } else {
            EXPECT_TRUE(events.begun().empty()) << "step " << step;
            EXPECT_TRUE(events.ended().empty()) << "step " << step;
        }
    }
    // The shift took more than one value on the way: the pair crossed the boundary.
    EXPECT_NE(std::find(shifts.begin(), shifts.end(), std::array<std::int32_t, 3>{1, 0, 0}), shifts.end());
    EXPECT_NE(std::find(shifts.begin(), shifts.end(), std::array<std::int32_t, 3>{0, 0, 0}), shifts.end());
    const std::vector<Box<Real, Dim>> apart{at(1, 2), at(5, 2), at(5, 6)};
    detector.detect(apart, domain, pairs, events);
    EXPECT_TRUE(pairs.empty());
    EXPECT_EQ(events.ended().size(), 1u);
}

TEST(PeriodicDomainCheck, MessagesGiveTheBoundsInShortestForm) {
    auto message = [](const PeriodicDomain<double, 3>& domain) {
        try {
            check_domain(domain);
        } catch (const ArgumentError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    // A period that overflows a double: said so, with the bounds as written, not 300 digits.
    const std::string wide = message(PeriodicDomain<double, 3>{}.wrap(0, -1e308, 1e308));
    EXPECT_NE(wide.find("[-1e+308, 1e+308)"), std::string::npos) << wide;
    EXPECT_NE(wide.find("overflows"), std::string::npos) << wide;
    EXPECT_LT(wide.size(), 160u) << wide;
    const std::string empty = message(PeriodicDomain<double, 3>{}.wrap(1, 0.1, 0.1));
    EXPECT_NE(empty.find("the y interval [0.1, 0.1) is empty"), std::string::npos) << empty;
    const std::string tiny = message(PeriodicDomain<double, 3>{}.wrap(2, 1e-6, 1e-320));
    EXPECT_NE(tiny.find("[1e-06, 1e-320)"), std::string::npos) << tiny;
    // Subnormal bounds are bounds like any other.
    EXPECT_EQ(message(PeriodicDomain<double, 3>{}.wrap(0, 1e-320, 2e-320)), "no error");
}

}  // namespace
}  // namespace smb::test
