// SPDX-License-Identifier: MIT
// Detector::suggested_order() and follow_suggested_order(): every index once, after a detection
// over the whole array; a caller that renumbers its bodies by it, telling the detector or not,
// keeps getting every pair (against brute force, over steps with motion, jumps, swap-removes and
// appended bodies); once followed, still boxes are read in the array's own order; and it is
// offered only where the cuts read the whole array (not after the skin, filters split into
// classes, a periodic detection or a rejected call).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/detector_shapes.hpp"
#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "smb/detector.hpp"
#include "smb/filter.hpp"
#include "smb/periodic.hpp"

namespace smb::test {
namespace {

/// Whether `order` holds every index below `n` once.
::testing::AssertionResult every_index_once(std::span<const std::uint32_t> order, std::size_t n) {
    if (order.size() != n) return ::testing::AssertionFailure() << order.size() << " indices for " << n << " boxes";
    std::vector<std::uint32_t> sorted(order.begin(), order.end());
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < n; ++i) {
        if (sorted[i] != i) return ::testing::AssertionFailure() << "index " << i << " is not there once";
    }
    return ::testing::AssertionSuccess();
}

template <typename T>
class DetectorOrderTest : public ::testing::Test {
protected:
    using Real = typename T::real_type;
    static constexpr int Dim = T::dimension;
    using BoxT = Box<Real, Dim>;

    static BoxT new_box(Random& random) { return random_box<Real, Dim>(random, 0, 16, 0.3, 1.2); }

    /// A simulation's arrays: the boxes and a name for each body that follows it through every
    /// renumbering, so that the pairs can be checked by body.
    struct Bodies {
        std::vector<BoxT> boxes;
        std::vector<std::uint64_t> names;
    };

    static void renumber(Bodies& bodies, std::span<const std::uint32_t> order) {
        Bodies next;
        for (const std::uint32_t index : order) {
            next.boxes.push_back(bodies.boxes[index]);
            next.names.push_back(bodies.names[index]);
        }
        bodies = next;
    }

    /// The pairs of `pairs` (indices) by name, sorted; the same of brute force.
    static std::vector<Pair> by_name(const std::vector<Pair>& pairs, const Bodies& bodies) {
        std::vector<Pair> named;
        for (const Pair& pair : pairs) {
            const std::uint64_t a = bodies.names[pair.a];
            const std::uint64_t b = bodies.names[pair.b];
            named.push_back(a < b ? Pair{a, b} : Pair{b, a});
        }
        sort_pairs(named);
        return named;
    }
};

TYPED_TEST_SUITE(DetectorOrderTest, Shapes, ShapeNames);

TYPED_TEST(DetectorOrderTest, RenumberingByItKeepsEveryPairOverManySteps) {
    using TestBox = typename TestFixture::BoxT;
    using TestReal = typename TestFixture::Real;
    constexpr int kDim = TestFixture::Dim;
    for (const std::size_t threads : {std::size_t{1}, std::size_t{3}}) {
        SCOPED_TRACE(::testing::Message() << "threads " << threads);
        Random random(17 + threads);
        DetectorSettings settings;
        settings.threads = threads;
        settings.target_cell_population = 6;
        Detector<TestReal, kDim> detector(settings);
        typename TestFixture::Bodies bodies;
        std::uint64_t next_name = 0;
        for (int i = 0; i < 1500; ++i) {
            bodies.boxes.push_back(TestFixture::new_box(random));
            bodies.names.push_back(next_name++);
        }
        for (int step = 0; step < 40; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            for (TestBox& box : bodies.boxes)
                box = chance(random, 0.01) ? TestFixture::new_box(random)
                                           : perturbed<TestReal, kDim>(random, box, 0.03, 0.01);
            if (step % 6 == 2) {  // swap-removes
                for (int k = 0; k < 60; ++k) {
                    const std::size_t at = uniform_index(random, bodies.boxes.size());
                    bodies.boxes[at] = bodies.boxes.back();
                    bodies.names[at] = bodies.names.back();
                    bodies.boxes.pop_back();
                    bodies.names.pop_back();
                }
            }
            if (step % 6 == 4) {
                for (int k = 0; k < 70; ++k) {
                    bodies.boxes.push_back(TestFixture::new_box(random));
                    bodies.names.push_back(next_name++);
                }
            }
            std::vector<Pair> pairs;
            detector.detect(bodies.boxes, pairs);
            const std::vector<Pair> expected =
                TestFixture::by_name(brute_force_pairs<TestReal, kDim>(std::span<const TestBox>(bodies.boxes)), bodies);
            EXPECT_TRUE(same_pairs(TestFixture::by_name(pairs, bodies), expected));
            const std::span<const std::uint32_t> order = detector.suggested_order();
            ASSERT_TRUE(every_index_once(order, bodies.boxes.size()));
            // Renumbered every fifth step, the detector told every other time; in between the
            // order drifts with the motion.
            if (step % 5 == 0) {
                TestFixture::renumber(bodies, order);
                if (step % 10 == 0) detector.follow_suggested_order();
            }
            if (::testing::Test::HasFailure()) return;
        }
    }
}

TYPED_TEST(DetectorOrderTest, OnceFollowedTheArrayIsReadInItsOwnOrder) {
    using TestBox = typename TestFixture::BoxT;
    Random random(5);
    typename TestFixture::Bodies bodies;
    for (std::uint64_t i = 0; i < 3000; ++i) {
        bodies.boxes.push_back(TestFixture::new_box(random));
        bodies.names.push_back(i);
    }
    // Two detectors over the same array, one told of the renumbering and one not.
    DetectorSettings settings;
    settings.profile = true;  // for the x sort's insertion moves
    Detector<typename TestFixture::Real, TestFixture::Dim> told(settings);
    Detector<typename TestFixture::Real, TestFixture::Dim> untold(settings);
    std::vector<Pair> pairs;
    told.detect(bodies.boxes, pairs);
    untold.detect(bodies.boxes, pairs);
    const std::vector<std::uint32_t> order(told.suggested_order().begin(), told.suggested_order().end());
    ASSERT_TRUE(
        std::equal(order.begin(), order.end(), untold.suggested_order().begin(), untold.suggested_order().end()));
    TestFixture::renumber(bodies, order);
    told.follow_suggested_order();
    told.detect(bodies.boxes, pairs);
    const std::vector<Pair> expected =
        brute_force_pairs<typename TestFixture::Real, TestFixture::Dim>(std::span<const TestBox>(bodies.boxes));
    EXPECT_TRUE(same_pairs(pairs, expected));
    untold.detect(bodies.boxes, pairs);
    EXPECT_TRUE(same_pairs(pairs, expected));
    // The told detector read the boxes in the order it will keep reading them in while they
    // stand still; the other one read them in the old order's places and sorted them afresh.
    const std::size_t told_moves = told.last_profile().sort_moves;
    const std::size_t untold_moves = untold.last_profile().sort_moves;
    told.detect(bodies.boxes, pairs);
    EXPECT_EQ(told_moves, told.last_profile().sort_moves);
    EXPECT_GT(untold_moves, 2 * told_moves);
    untold.detect(bodies.boxes, pairs);
    // The boxes stood still: from now on both read the array in its own order.
    std::vector<std::uint32_t> identity(bodies.boxes.size());
    std::iota(identity.begin(), identity.end(), 0U);
    for (const auto* detector : {&told, &untold}) {
        const std::span<const std::uint32_t> next = detector->suggested_order();
        EXPECT_TRUE(std::equal(next.begin(), next.end(), identity.begin(), identity.end()));
    }
}

TYPED_TEST(DetectorOrderTest, IsOfferedOnlyAfterTheCutsReadTheWholeArray) {
    using TestBox = typename TestFixture::BoxT;
    using TestReal = typename TestFixture::Real;
    constexpr int kDim = TestFixture::Dim;
    Random random(9);
    std::vector<TestBox> boxes;
    for (int i = 0; i < 800; ++i) boxes.push_back(TestFixture::new_box(random));
    Detector<TestReal, kDim> detector;
    EXPECT_TRUE(detector.suggested_order().empty()) << "before any detection";
    std::vector<Pair> pairs;
    detector.detect(boxes, pairs);
    EXPECT_TRUE(every_index_once(detector.suggested_order(), boxes.size()));

    // Filters that split the boxes into two classes: each class is detected apart.
    std::vector<Filter> filters(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) filters[i] = i % 2 == 0 ? Filter{1, 1} : Filter{2, 2};
    DetectFilters split;
    split.filters = filters;
    detector.detect(boxes, split, pairs);
    EXPECT_TRUE(detector.suggested_order().empty()) << "after classes";
    detector.detect(boxes, pairs);
    EXPECT_TRUE(every_index_once(detector.suggested_order(), boxes.size()));

    PeriodicDomain<TestReal, kDim> domain;
    for (int k = 0; k < kDim; ++k) domain.wrap(k, -1, 20);
    std::vector<PeriodicPair> periodic;
    detector.detect(boxes, domain, periodic);
    EXPECT_TRUE(detector.suggested_order().empty()) << "after a periodic detection";
    detector.detect(boxes, pairs);

    // A rejected call leaves nothing to offer: the order would be of another array.
    std::vector<TestBox> broken = boxes;
    broken[3].min[0] = std::numeric_limits<TestReal>::quiet_NaN();
    EXPECT_THROW(detector.detect(broken, pairs), InvalidBoxError);
    EXPECT_TRUE(detector.suggested_order().empty()) << "after a rejected call";
    detector.detect(boxes, pairs);
    EXPECT_TRUE(every_index_once(detector.suggested_order(), boxes.size()));

    detector.clear();
    EXPECT_TRUE(detector.suggested_order().empty()) << "after clear()";
    detector.follow_suggested_order();  // nothing to follow: no effect
    detector.detect(boxes, pairs);
    EXPECT_TRUE(same_pairs(pairs, brute_force_pairs<TestReal, kDim>(std::span<const TestBox>(boxes))));

    DetectorSettings skinned;
    skinned.skin = 0.1;
    Detector<TestReal, kDim> with_skin(skinned);
    with_skin.detect(boxes, pairs);
    with_skin.detect(boxes, pairs);
    if (with_skin.candidates().available) {
        EXPECT_TRUE(with_skin.suggested_order().empty()) << "after the skin";
    }
    Detector<TestReal, kDim> moved_from(std::move(with_skin));
    EXPECT_TRUE(with_skin.suggested_order().empty()) << "moved from";  // NOLINT(bugprone-use-after-move)
}

}  // namespace
}  // namespace smb::test
