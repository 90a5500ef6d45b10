// SPDX-License-Identifier: MIT
// Detector's periodic detection at the edges of the domain, against the brute force over the 3^D
// images: boxes touching across the boundary, at lo and just below hi, far outside the domain,
// translated by whole periods; a domain one box wide; rejected input, which changes nothing, and
// its messages. tests/api/test_periodic_detector.cpp runs random scenes over many steps.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "reference/periodic_brute_force.hpp"
#include "reference/periodic_detector_test.hpp"
#include "reference/world_types.hpp"
#include "smb/detector.hpp"

namespace smb::test {
namespace {

TYPED_TEST_SUITE(PeriodicDetectorTest, Shapes, ShapeNames);

TYPED_TEST(PeriodicDetectorTest, BoxesTouchingAcrossTheBoundary) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
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
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
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
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
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
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
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
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
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
