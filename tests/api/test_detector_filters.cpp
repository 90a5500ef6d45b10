// SPDX-License-Identifier: MIT
// Detector filters (smb/filter.hpp) against brute force: random bits, static flags and a
// predicate over calls whose boxes move and whose array grows and shrinks; and spans of the
// wrong length.

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "smb/detector.hpp"
#include "smb/filter.hpp"

namespace smb::test {
namespace {

template <typename DetectorType>
class DetectorFiltersTest : public ::testing::Test {};

using DetectorTypes = ::testing::Types<Detector2f, Detector2d, Detector3f, Detector3d>;
TYPED_TEST_SUITE(DetectorFiltersTest, DetectorTypes);

TYPED_TEST(DetectorFiltersTest, RandomFiltersStaticsAndPredicateMatchBruteForce) {
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    Random random(7);
    const double space = std::pow(400 * std::pow(1.5, Dim) / 0.35, 1.0 / Dim);
    std::vector<Box<Real, Dim>> boxes;
    std::vector<Filter> filters;
    std::vector<std::uint8_t> statics;
    TypeParam detector;
    for (int call = 0; call < 20; ++call) {
        SCOPED_TRACE(::testing::Message() << "call " << call);
        const std::size_t n = 350 + uniform_index(random, 100);
        boxes.resize(n, Box<Real, Dim>{});
        filters.resize(n);
        statics.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            boxes[i] = call == 0 || chance(random, 0.01) ? random_box<Real, Dim>(random, 0, space, 1.0, 2.0)
                                                         : perturbed(random, boxes[i], 1e-3 * space, 1e-2);
            if (call == 0 || chance(random, 0.05)) {
                filters[i] = Filter{static_cast<std::uint32_t>(uniform_index(random, 4)),
                                    static_cast<std::uint32_t>(uniform_index(random, 8))};
                statics[i] = chance(random, 0.3) ? 1 : 0;
            }
        }
        DetectFilters f;
        f.filters = filters;
        f.statics = statics;
        if (call % 2 == 1) f.predicate = [](BoxId a, BoxId b) { return (a * 7 + b) % 5 != 0; };
        std::vector<Pair> expected;
        for (const Pair& p : brute_force_pairs<Real, Dim>(boxes)) {
            if (statics[p.a] != 0 && statics[p.b] != 0) continue;
            if (!filters_pass(filters[p.a], filters[p.b])) continue;
            if (f.predicate && !f.predicate(p.a, p.b)) continue;
            expected.push_back(p);
        }
        std::vector<Pair> pairs;
        const DetectStats stats = detector.detect(boxes, f, pairs);
        EXPECT_EQ(stats.pairs, pairs.size());
        EXPECT_EQ(detector.last_stats().pairs, pairs.size());
        ASSERT_TRUE(same_pairs(pairs, expected));
    }
}

TYPED_TEST(DetectorFiltersTest, LayersThatIgnoreEachOtherMatchBruteForce) {
    // Layers whose masks meet only their own category (interaction classes detected apart), a
    // debris set linked to layer 1, boxes that pair with nothing; some calls link every layer
    // through a box that meets them all (one class again), then it leaves. Boxes move, teleport,
    // change layer, and the array grows and shrinks.
    using Real = typename TypeParam::real_type;
    constexpr int Dim = TypeParam::dimension;
    Random random(11);
    const double space = std::pow(500 * std::pow(1.5, Dim) / 0.5, 1.0 / Dim);
    const std::vector<Filter> layers{{1, 1}, {2, 2}, {4, 4}, {8, 8}, {16, 1}, {32, 0}, {0, 255}};
    const auto random_layer = [&] { return layers[uniform_index(random, layers.size())]; };
    std::vector<Box<Real, Dim>> boxes;
    std::vector<Filter> filters;
    std::vector<std::uint8_t> statics;
    TypeParam detector;
    for (int call = 0; call < 24; ++call) {
        SCOPED_TRACE(::testing::Message() << "call " << call);
        const std::size_t n = 400 + uniform_index(random, 150);
        const std::size_t held = boxes.size();
        boxes.resize(n, Box<Real, Dim>{});
        filters.resize(n);
        statics.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const bool fresh = i >= held;
            boxes[i] = fresh || chance(random, 0.02) ? random_box<Real, Dim>(random, 0, space, 1.0, 2.5)
                                                     : perturbed(random, boxes[i], 1e-3 * space, 1e-2);
            if (fresh || chance(random, 0.03)) filters[i] = random_layer();
            statics[i] = chance(random, 0.1) ? 1 : 0;
        }
        const bool linked = call % 6 == 3;
        if (linked) filters[n / 2] = Filter{255, 255};
        DetectFilters f;
        f.filters = filters;
        if (call % 4 == 1) f.statics = statics;
        if (call % 5 == 2) f.predicate = [](BoxId a, BoxId b) { return (a + 3 * b) % 7 != 0; };
        std::vector<Pair> expected;
        for (const Pair& p : brute_force_pairs<Real, Dim>(boxes)) {
            if (!f.statics.empty() && statics[p.a] != 0 && statics[p.b] != 0) continue;
            if (!filters_pass(filters[p.a], filters[p.b])) continue;
            if (f.predicate && !f.predicate(p.a, p.b)) continue;
            expected.push_back(p);
        }
        std::vector<Pair> pairs;
        const DetectStats stats = detector.detect(boxes, f, pairs);
        EXPECT_EQ(stats.pairs, pairs.size());
        EXPECT_EQ(stats.boxes, n);
        EXPECT_EQ(detector.last_stats().pairs, pairs.size());
        EXPECT_NE(detector.last_precision(), HeldPrecision::none);
        ASSERT_TRUE(same_pairs(pairs, expected));
        if (linked) filters[n / 2] = random_layer();
    }
    detector.clear();
    EXPECT_EQ(detector.last_precision(), HeldPrecision::none);
}

TEST(DetectorFilters, AnInvalidBoxIsNamedByItsIndexWhenBoxesAreLeftOut) {
    Detector3f detector;
    std::vector<Box3f> boxes(3, Box3f{{0, 0, 0}, {1, 1, 1}});
    boxes[2].min[1] = 2;  // min > max
    const std::vector<Filter> filters = {Filter{0, 0}, Filter{}, Filter{}};
    DetectFilters f;
    f.filters = filters;
    std::vector<Pair> pairs;
    try {
        detector.detect(boxes, f, pairs);
        FAIL() << "no error";
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("box 2"), std::string::npos) << error.what();
    }
    boxes[2] = boxes[1];
    const DetectStats stats = detector.detect(boxes, f, pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{1, 2}}));
    EXPECT_EQ(stats.boxes, 3u);
}

TEST(DetectorFilters, SpansOfTheWrongLengthThrowAndChangeNothing) {
    Detector2d detector;
    const std::vector<Box2d> boxes = {Box2d{{0, 0}, {1, 1}}, Box2d{{1, 1}, {2, 2}}};
    const std::vector<Filter> one(1);
    const std::vector<std::uint8_t> three(3, 0);
    std::vector<Pair> pairs = {{5, 6}};
    DetectFilters f;
    f.filters = one;
    EXPECT_THROW(detector.detect(boxes, f, pairs), ArgumentError);
    f.filters = {};
    f.statics = three;
    EXPECT_THROW(detector.detect(boxes, f, pairs), ArgumentError);
    EXPECT_EQ(pairs, (std::vector<Pair>{{5, 6}}));
    f.statics = {};
    detector.detect(boxes, f, pairs);  // no filter: the plain detection
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 1}}));
}

}  // namespace
}  // namespace smb::test
