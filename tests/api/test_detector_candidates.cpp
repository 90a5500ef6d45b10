// SPDX-License-Identifier: MIT
// smb::Detector::candidates(): the Verlet list a Detector with a skin keeps, against brute force
// over many steps of motion: it holds every pair of boxes that overlap once grown by its margin,
// only pairs within two skins each where boxes keep their sizes, each pair once with a < b; the
// same list whatever the threads; and no list where there is no skin list to give.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <span>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/detector_shapes.hpp"
#include "reference/random_boxes.hpp"
#include "smb/detector.hpp"

namespace smb::test {
namespace {

#if defined(SMB_TEST_REDUCED)
constexpr std::size_t kScale = 4;
#else
constexpr std::size_t kScale = 1;
#endif

template <typename T>
class DetectorCandidatesTest : public ::testing::Test {
protected:
    using Real = typename T::real_type;
    static constexpr int Dim = T::dimension;
    using BoxT = Box<Real, Dim>;

    /// A box of side `side` (all alike, so that a box's fat box is its own) in a cube of side
    /// `space` around `centre`.
    static BoxT new_box(Random& random, double centre, double space, double side) {
        std::array<double, Dim> middle{};
        std::array<double, Dim> half{};
        for (int k = 0; k < Dim; ++k) {
            middle[k] = centre + uniform(random, -0.5, 0.5) * space;
            half[k] = 0.5 * side;
        }
        return box_around<Real, Dim>(middle, half);
    }

    /// Moves every box rigidly by up to `shift` on every axis.
    static void move(Random& random, std::vector<BoxT>& boxes, double shift) {
        for (BoxT& box : boxes) {
            for (int k = 0; k < Dim; ++k) {
                const auto delta = static_cast<Real>(uniform(random, -shift, shift));
                box.min[k] += delta;
                box.max[k] += delta;
            }
        }
    }

    static BoxT grown(const BoxT& box, double by) {
        Box<double, Dim> wide;
        for (int k = 0; k < Dim; ++k) {
            wide.min[k] = static_cast<double>(box.min[k]) - by;
            wide.max[k] = static_cast<double>(box.max[k]) + by;
        }
        BoxT out;
        for (int k = 0; k < Dim; ++k) {
            // Rounded outwards: the grown box holds the exact one.
            out.min[k] = static_cast<Real>(wide.min[k]);
            if (static_cast<double>(out.min[k]) > wide.min[k]) out.min[k] = std::nextafter(out.min[k], Real(-1e30));
            out.max[k] = static_cast<Real>(wide.max[k]);
            if (static_cast<double>(out.max[k]) < wide.max[k]) out.max[k] = std::nextafter(out.max[k], Real(1e30));
        }
        return out;
    }

    /// Checks one detection's list: pairs once each with a < b inside the array, every pair of
    /// boxes grown by the margin, and (when `near` > 0) only pairs of boxes grown by `near` that
    /// overlap. Returns whether a list was there.
    static bool check(Detector<Real, Dim>& detector, const std::vector<BoxT>& boxes, const std::vector<Pair>& detected,
                      double skin, double near) {
        const CandidatePairs list = detector.candidates();
        if (!list.available) {
            EXPECT_TRUE(list.pairs.empty());
            return false;
        }
        EXPECT_GE(list.margin, 0.0);
        EXPECT_LE(list.margin, skin);
        std::vector<Pair> sorted(list.pairs.begin(), list.pairs.end());
        sort_pairs(sorted);
        EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) << "a pair listed twice";
        for (const Pair& pair : sorted) {
            EXPECT_LT(pair.a, pair.b);
            EXPECT_LT(pair.b, boxes.size());
        }
        for (const Pair& pair : detected) {
            EXPECT_TRUE(std::binary_search(sorted.begin(), sorted.end(), pair))
                << "overlap " << pair.a << " " << pair.b;
        }
        std::vector<BoxT> wide;
        for (const BoxT& box : boxes) wide.push_back(grown(box, list.margin));
        for (const Pair& pair : brute_force_pairs<Real, Dim>(std::span<const BoxT>(wide))) {
            EXPECT_TRUE(std::binary_search(sorted.begin(), sorted.end(), pair))
                << "pair " << pair.a << " " << pair.b << " within the margin " << list.margin << " is missing";
            if (::testing::Test::HasFailure()) return true;
        }
        if (near > 0) {
            for (const Pair& pair : sorted) {
                EXPECT_TRUE(overlaps(grown(boxes[pair.a], near), grown(boxes[pair.b], near)))
                    << "pair " << pair.a << " " << pair.b << " is farther than two skins each";
                if (::testing::Test::HasFailure()) return true;
            }
        }
        return true;
    }
};

TYPED_TEST_SUITE(DetectorCandidatesTest, Shapes, ShapeNames);

TYPED_TEST(DetectorCandidatesTest, HoldsEveryPairWithinItsMarginOverRigidMotion) {
    using R = typename TestFixture::Real;
    constexpr int D = TestFixture::Dim;
    for (const double centre : {0.0, 1000.0}) {
        for (const double skin : {0.05, 0.3}) {
            SCOPED_TRACE(::testing::Message() << "skin " << skin << ", centre " << centre);
            Random random(7);
            const std::size_t n = 800 / kScale;
            const double space = std::cbrt(static_cast<double>(n)) * 1.4;
            std::vector<typename TestFixture::BoxT> boxes;
            for (std::size_t i = 0; i < n; ++i) boxes.push_back(TestFixture::new_box(random, centre, space, 1.0));
            DetectorSettings settings;
            settings.skin = skin;
            Detector<R, D> detector(settings);
            std::vector<Pair> pairs;
            int listed = 0;
            double after_rebuild = skin;
            for (int step = 0; step < 60 / static_cast<int>(kScale); ++step) {
                SCOPED_TRACE(::testing::Message() << "step " << step);
                if (step > 0) TestFixture::move(random, boxes, skin / 8);
                // A few jump: they leave their fat box and get a new one where they land.
                if (step % 5 == 4) boxes[random() % n] = TestFixture::new_box(random, centre, space, 1.0);
                const DetectStats stats = detector.detect(boxes, pairs);
                // Rounding of the boxes as held (floats away from 0) and of the rigid moves.
                const double slack = 1e-5 * (std::abs(centre) + space) + 1e-6;
                listed += TestFixture::check(detector, boxes, pairs, skin, 2 * skin + slack) ? 1 : 0;
                if (stats.skin_rebuilt) after_rebuild = std::min(after_rebuild, detector.candidates().margin);
                if (::testing::Test::HasFailure()) return;
            }
            EXPECT_GT(listed, 50 / static_cast<int>(kScale));
            EXPECT_GT(after_rebuild, 0.9 * skin) << "the margin right after a rebuild is about the skin";
        }
    }
}

TYPED_TEST(DetectorCandidatesTest, HoldsEveryPairWithinItsMarginOverASimulationsLife) {
    using R = typename TestFixture::Real;
    constexpr int D = TestFixture::Dim;
    Random random(11);
    const std::size_t n = 700 / kScale;
    const double space = std::cbrt(static_cast<double>(n)) * 1.5;
    std::vector<typename TestFixture::BoxT> boxes;
    for (std::size_t i = 0; i < n; ++i)
        boxes.push_back(TestFixture::new_box(random, 0, space, uniform(random, 0.5, 1.5)));
    DetectorSettings settings;
    settings.skin = 0.2;
    Detector<R, D> detector(settings);
    std::vector<Pair> pairs;
    std::vector<typename TestFixture::BoxT> put_aside;
    int listed = 0;
    for (int step = 0; step < 50 / static_cast<int>(kScale); ++step) {
        SCOPED_TRACE(::testing::Message() << "step " << step);
        if (step > 0) {
            TestFixture::move(random, boxes, 0.02);
            for (int removal = 0; removal < 3; ++removal) {  // swap-remove
                const std::size_t victim = random() % boxes.size();
                boxes[victim] = boxes.back();
                boxes.pop_back();
            }
            for (int birth = 0; birth < 3; ++birth) boxes.push_back(TestFixture::new_box(random, 0, space, 1.0));
            if (step % 13 == 5) {
                put_aside.assign(boxes.end() - 40 / kScale, boxes.end());
                boxes.resize(boxes.size() - put_aside.size());
            } else if (step % 13 == 7) {
                boxes.insert(boxes.end(), put_aside.begin(), put_aside.end());
            }
        }
        detector.detect(boxes, pairs);
        listed += TestFixture::check(detector, boxes, pairs, settings.skin, 0) ? 1 : 0;
        if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(listed, 40 / static_cast<int>(kScale));
}

TEST(DetectorCandidates, SameListWhateverTheThreads) {
    // Enough candidates for the pass over them to run in blocks on several threads.
    const std::size_t n = 24000 / kScale;
    Random random(3);
    const double space = std::cbrt(static_cast<double>(n)) * 1.3;
    std::vector<Box3d> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        const std::array<double, 3> middle{uniform(random, 0, space), uniform(random, 0, space),
                                           uniform(random, 0, space)};
        boxes.push_back(box_around<double, 3>(middle, {0.5, 0.5, 0.5}));
    }
    DetectorSettings one;
    one.skin = 0.1;
    DetectorSettings two = one;
    two.threads = 2;
    Detector3d serial(one);
    Detector3d parallel(two);
    std::vector<Pair> pairs_serial;
    std::vector<Pair> pairs_parallel;
    for (int step = 0; step < 12; ++step) {
        SCOPED_TRACE(::testing::Message() << "step " << step);
        for (Box3d& box : boxes) {
            for (int k = 0; k < 3; ++k) {
                const double delta = uniform(random, -0.02, 0.02);
                box.min[k] += delta;
                box.max[k] += delta;
            }
        }
        serial.detect(boxes, pairs_serial);
        parallel.detect(boxes, pairs_parallel);
        const CandidatePairs a = serial.candidates();
        const CandidatePairs b = parallel.candidates();
        ASSERT_TRUE(a.available);
        ASSERT_TRUE(b.available);
        if (kScale == 1) {
            EXPECT_GT(a.pairs.size(), std::size_t{1} << 15) << "too few candidates for threads";
        }
        EXPECT_EQ(a.margin, b.margin);
        EXPECT_TRUE(std::equal(a.pairs.begin(), a.pairs.end(), b.pairs.begin(), b.pairs.end()));
        EXPECT_EQ(pairs_serial, pairs_parallel);
    }
}

TEST(DetectorCandidates, NoListWithoutASkinList) {
    std::vector<Box3d> boxes{Box3d{{0, 0, 0}, {1, 1, 1}}, Box3d{{1.05, 0, 0}, {2, 1, 1}}, Box3d{{5, 5, 5}, {6, 6, 6}}};
    std::vector<Pair> pairs;

    Detector3d plain;
    EXPECT_FALSE(plain.candidates().available);  // nothing detected yet
    plain.detect(boxes, pairs);
    EXPECT_FALSE(plain.candidates().available);  // no skin
    EXPECT_TRUE(plain.candidates().pairs.empty());

    DetectorSettings settings;
    settings.skin = 0.1;
    Detector3d skinned(settings);
    skinned.detect(boxes, pairs);
    CandidatePairs list = skinned.candidates();
    ASSERT_TRUE(list.available);
    ASSERT_EQ(list.pairs.size(), 1U);  // 0 and 1 are 0.05 apart: candidates, not a pair
    EXPECT_EQ(list.pairs[0], (Pair{0, 1}));
    EXPECT_TRUE(pairs.empty());
    EXPECT_NEAR(list.margin, 0.1, 1e-6);

    // A filtered detection that leaves box 2 out works on other indices: no list.
    std::vector<Filter> filters{Filter{}, Filter{}, Filter{0, 0}};
    skinned.detect(boxes, DetectFilters{filters, {}, {}}, pairs);
    EXPECT_FALSE(skinned.candidates().available);
    skinned.detect(boxes, pairs);
    EXPECT_TRUE(skinned.candidates().available);

    skinned.detect(std::span<const Box3d>(), pairs);
    EXPECT_FALSE(skinned.candidates().available);  // empty array
    skinned.detect(boxes, pairs);
    skinned.clear();
    EXPECT_FALSE(skinned.candidates().available);
    skinned.detect(boxes, pairs);
    Detector3d moved(std::move(skinned));
    EXPECT_TRUE(moved.candidates().available);
    EXPECT_FALSE(skinned.candidates().available);  // NOLINT(bugprone-use-after-move): documented state

    // A detection that throws leaves no list behind.
    boxes[1].min[0] = std::nan("");
    EXPECT_THROW(moved.detect(boxes, pairs), InvalidBoxError);
    EXPECT_FALSE(moved.candidates().available);
}

}  // namespace
}  // namespace smb::test
