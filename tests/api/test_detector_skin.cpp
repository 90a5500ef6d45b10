// SPDX-License-Identifier: MIT
// smb::Detector with a skin (DetectorSettings::skin): the candidate list kept between detections
// against brute force, over many steps of small motion with jumps, swap-removals, appends, an
// array that shrinks and grows back, skins from tight to far too wide; and the guarantees the
// Detector gives without a skin (order whatever the threads, throwing sinks, bad input).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/brute_force.hpp"
#include "reference/detector_shapes.hpp"
#include "reference/pair_check.hpp"
#include "reference/random_boxes.hpp"
#include "smb/detector.hpp"
#include "smb/world.hpp"

namespace smb::test {
namespace {

template <typename T>
class DetectorSkinTest : public ::testing::Test {
protected:
    using Real = typename T::real_type;
    static constexpr int Dim = T::dimension;
    using BoxT = Box<Real, Dim>;

    /// A box of side 0.5 to 1.5 centred in a cube of side `space` around `centre`.
    static BoxT new_box(Random& random, double centre, double space, double side = 1) {
        std::array<double, Dim> middle{};
        std::array<double, Dim> half{};
        for (int k = 0; k < Dim; ++k) {
            middle[k] = centre + uniform(random, -0.5, 0.5) * space;
            half[k] = 0.5 * side * uniform(random, 0.5, 1.5);
        }
        return box_around<Real, Dim>(middle, half);
    }

    /// Moves every box by up to `shift` on every axis; sides change a little too.
    static void move(Random& random, std::vector<BoxT>& boxes, double shift) {
        for (BoxT& box : boxes) {
            for (int k = 0; k < Dim; ++k) {
                const double delta = uniform(random, -shift, shift);
                const double grow = uniform(random, -0.1 * shift, 0.1 * shift);
                box.min[k] = static_cast<Real>(static_cast<double>(box.min[k]) + delta);
                box.max[k] = std::max(box.min[k], static_cast<Real>(static_cast<double>(box.max[k]) + delta + grow));
            }
        }
    }

    static void expect_brute_force(const std::vector<Pair>& pairs, const std::vector<BoxT>& boxes) {
        EXPECT_TRUE(same_pairs(pairs, brute_force_pairs<Real, Dim>(std::span<const BoxT>(boxes)),
                               [&boxes](BoxId id) { return describe(boxes.at(id)); }));
    }

    /// A simulation's life: small motion every step, a few bodies jumping, swap-removed and
    /// appended, and now and then the array cut short and grown back. Returns how many steps
    /// kept the candidates (no rebuild), so that a test can see the kept path ran.
    std::size_t drive(std::uint64_t seed, const DetectorSettings& settings, double centre, double shift, int steps = 40,
                      std::size_t n = 700) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed << ", skin " << settings.skin << ", centre " << centre
                                          << ", threads " << settings.threads);
        Random random(seed);
        const double space = std::cbrt(static_cast<double>(n)) * 1.6;
        std::vector<BoxT> boxes;
        for (std::size_t i = 0; i < n; ++i) boxes.push_back(new_box(random, centre, space));
        Detector<Real, Dim> detector(settings);
        std::size_t kept = 0;
        std::vector<BoxT> put_aside;
        for (int step = 0; step < steps; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            if (step > 0) {
                move(random, boxes, shift);
                for (int jump = 0; jump < 3; ++jump) boxes[random() % boxes.size()] = new_box(random, centre, space);
                for (int removal = 0; removal < 4; ++removal) {
                    const std::size_t victim = random() % boxes.size();
                    boxes[victim] = boxes.back();
                    boxes.pop_back();
                }
                for (int birth = 0; birth < 3; ++birth) boxes.push_back(new_box(random, centre, space));
                if (step % 13 == 5) {
                    put_aside.assign(boxes.end() - 50, boxes.end());
                    boxes.resize(boxes.size() - 50);
                } else if (step % 13 == 7) {
                    boxes.insert(boxes.end(), put_aside.begin(), put_aside.end());
                }
            }
            std::vector<Pair> pairs;
            const DetectStats stats = detector.detect(boxes, pairs);
            EXPECT_EQ(stats.pairs, pairs.size());
            expect_brute_force(pairs, boxes);
            if (::testing::Test::HasFailure()) return kept;
            kept += (stats.skin_candidates > 0 && !stats.skin_rebuilt) ? 1U : 0U;
        }
        return kept;
    }
};

TYPED_TEST_SUITE(DetectorSkinTest, Shapes, ShapeNames);

TYPED_TEST(DetectorSkinTest, MatchesBruteForceOverAManyStepLifeWithEverySkin) {
    for (const double skin : {0.01, 0.1, 0.4, 2.0}) {
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
            DetectorSettings settings;
            settings.skin = skin;
            const std::size_t kept = this->drive(seed, settings, 0.0, 0.01);
            if (skin >= 0.1) {
                EXPECT_GT(kept, 20U) << "skin " << skin << ": the kept candidates were not used";
            }
            settings.target_cell_population = 3;
            this->drive(seed + 10, settings, 0.0, 0.03);
        }
    }
}

TYPED_TEST(DetectorSkinTest, MatchesBruteForceFarFromTheOriginAndWhenEverythingMovesFar) {
    using TestReal = typename TestFixture::Real;
    DetectorSettings settings;
    settings.skin = 0.2;
    // Far: for doubles the held floats are shifted to the scene's middle; for floats the grid of
    // representable values is coarse (1/16 at 1e6), which makes the fat boxes coarser only.
    const double far = std::is_same_v<TestReal, float> ? 1e6 : 3e9;
    this->drive(3, settings, far, 0.01);
    // Every box moves by more than the skin at every step: a rebuild or a crowd of refreshes
    // every time.
    this->drive(4, settings, 0.0, 0.5, 12);
}

TYPED_TEST(DetectorSkinTest, SettlesTouchingAndZeroSizeBoxes) {
    using TestBox = typename TestFixture::BoxT;
    constexpr int dim = TestFixture::Dim;
    std::vector<TestBox> boxes;
    // A lattice of unit boxes (every neighbour touches), and points on its corners.
    for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
            for (int l = 0; l < (dim == 3 ? 4 : 1); ++l) {
                TestBox box;
                TestBox point;
                const std::array<int, 3> at{i, j, l};
                for (int k = 0; k < dim; ++k) {
                    box.min[k] = static_cast<typename TestFixture::Real>(at[static_cast<std::size_t>(k)]);
                    box.max[k] = box.min[k] + 1;
                    point.min[k] = point.max[k] = box.min[k];
                }
                boxes.push_back(box);
                boxes.push_back(point);
            }
        }
    }
    DetectorSettings settings;
    settings.skin = 0.25;
    Detector<typename TestFixture::Real, dim> detector(settings);
    for (int step = 0; step < 4; ++step) {
        std::vector<Pair> pairs;
        detector.detect(boxes, pairs);
        this->expect_brute_force(pairs, boxes);
        boxes.push_back(boxes[static_cast<std::size_t>(step) * 7]);  // an identical box arrives
    }
}

TYPED_TEST(DetectorSkinTest, ReportsTheSamePairsInTheSameOrderWhateverTheThreadCount) {
    using TestBox = typename TestFixture::BoxT;
    std::vector<std::vector<Pair>> runs;
    for (std::size_t threads : {1U, 2U, 4U}) {
        Random random(21);
        std::vector<TestBox> boxes;
        for (int i = 0; i < 1500; ++i) boxes.push_back(this->new_box(random, 0, 14));
        DetectorSettings settings;
        settings.threads = threads;
        settings.skin = 0.1;
        Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
        std::vector<Pair> all;
        for (int step = 0; step < 6; ++step) {
            this->move(random, boxes, 0.02);
            boxes.push_back(this->new_box(random, 0, 14));
            std::vector<Pair> pairs;
            detector.detect(boxes, pairs);
            all.insert(all.end(), pairs.begin(), pairs.end());
        }
        runs.push_back(all);
    }
    EXPECT_EQ(runs[0], runs[1]);
    EXPECT_EQ(runs[0], runs[2]);
}

// Past 2^15 positions and candidates, the containment check and the candidate pass share
// their work among the threads (in blocks handed on in list order): the same pairs in the same
// order as one thread, and the same set as the detector without a skin (itself checked against
// brute force above), over steps that keep, refresh and drop candidates; a sink that throws
// on the threaded pass leaves the detector valid.
TYPED_TEST(DetectorSkinTest, OnManyBoxesSharesTheWorkAmongThreadsWithoutChangingThePairs) {
    using TestBox = typename TestFixture::BoxT;
    using TestDetector = Detector<typename TestFixture::Real, TestFixture::Dim>;
    const double space = TestFixture::Dim == 3 ? 40 : 260;
    std::vector<std::vector<Pair>> runs;
    for (std::size_t threads : {1U, 2U, 3U}) {
        SCOPED_TRACE(::testing::Message() << threads << " threads");
        Random random(31);
        std::vector<TestBox> boxes;
        for (int i = 0; i < 50000; ++i) boxes.push_back(this->new_box(random, 0, space));
        DetectorSettings settings;
        settings.threads = threads;
        settings.skin = 0.1;
        settings.pair_chunk_size = 1000;
        TestDetector detector(settings);
        TestDetector plain;
        std::vector<Pair> all;
        for (int step = 0; step < 6; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            this->move(random, boxes, 0.01);
            for (int jump = 0; jump < 50; ++jump) boxes[random() % boxes.size()] = this->new_box(random, 0, space);
            boxes.resize(boxes.size() - 20);
            if (step == 3) {
                int chunks = 0;
                EXPECT_THROW(detector.detect(boxes,
                                             [&chunks](std::span<const Pair>) {
                                                 if (++chunks == 7) throw std::runtime_error("sink full");
                                             }),
                             std::runtime_error);
            }
            std::vector<Pair> pairs;
            const DetectStats stats = detector.detect(boxes, pairs);
            EXPECT_GT(stats.skin_candidates, std::size_t{1} << 15);
            all.insert(all.end(), pairs.begin(), pairs.end());
            std::vector<Pair> expected;
            plain.detect(boxes, expected);
            sort_pairs(pairs);
            sort_pairs(expected);
            EXPECT_EQ(pairs, expected);
        }
        runs.push_back(all);
    }
    EXPECT_EQ(runs[0], runs[1]);
    EXPECT_EQ(runs[0], runs[2]);
}

TYPED_TEST(DetectorSkinTest, AThrowingSinkLeavesItValid) {
    using TestBox = typename TestFixture::BoxT;
    Random random(5);
    std::vector<TestBox> boxes;
    for (int i = 0; i < 1500; ++i) boxes.push_back(this->new_box(random, 0, 12, 2));
    DetectorSettings settings;
    settings.skin = 0.1;
    settings.pair_chunk_size = 64;
    Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
    std::vector<Pair> pairs;
    detector.detect(boxes, pairs);  // the candidates are built: the next throws on the kept path
    for (int step = 0; step < 3; ++step) {
        this->move(random, boxes, 0.01);
        boxes[static_cast<std::size_t>(step)] = this->new_box(random, 0, 12, 2);
        int chunks = 0;
        EXPECT_THROW(detector.detect(boxes,
                                     [&chunks, step](std::span<const Pair>) {
                                         if (++chunks == 2 + 5 * step) throw std::runtime_error("sink full");
                                     }),
                     std::runtime_error);
        detector.detect(boxes, pairs);
        this->expect_brute_force(pairs, boxes);
    }
}

TYPED_TEST(DetectorSkinTest, StepsAsideWhenTheSkinMakesFarTooManyCandidates) {
    using TestBox = typename TestFixture::BoxT;
    Random random(8);
    std::vector<TestBox> boxes;
    for (int i = 0; i < 1600; ++i) boxes.push_back(this->new_box(random, 0, 30));
    DetectorSettings settings;
    settings.skin = 1e6;  // every pair is a candidate: 1.3 million, past the cap of 32 per box
    Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
    for (int step = 0; step < 3; ++step) {
        std::vector<Pair> pairs;
        const DetectStats stats = detector.detect(boxes, pairs);
        EXPECT_EQ(stats.skin_candidates, 0U);
        this->expect_brute_force(pairs, boxes);
        this->move(random, boxes, 0.1);
    }
    EXPECT_LT(detector.bytes_held(), 200U * boxes.size());
}

TYPED_TEST(DetectorSkinTest, StepsAsideWhileTheBoxesMoveFartherThanTheSkin) {
    using TestBox = typename TestFixture::BoxT;
    // Every box moving ten times the skin; a tenth of them jumping (past the moved list's
    // limit of 64 for 2000 boxes at every step); 40 jumping (within it, but two such steps
    // pass it).
    for (const int jumps : {-1, 200, 40}) {
        SCOPED_TRACE(::testing::Message() << "jumps " << jumps);
        Random random(12);
        std::vector<TestBox> boxes;
        for (int i = 0; i < 2000; ++i) boxes.push_back(this->new_box(random, 0, 20));
        DetectorSettings settings;
        settings.skin = 0.05;
        Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
        std::vector<bool> skinned;
        for (int step = 0; step < 8; ++step) {
            std::vector<Pair> pairs;
            const DetectStats stats = detector.detect(boxes, pairs);
            skinned.push_back(stats.skin_candidates > 0);
            this->expect_brute_force(pairs, boxes);
            if (jumps < 0) {
                this->move(random, boxes, 0.5);
            } else {
                for (int jump = 0; jump < jumps; ++jump) boxes[random() % boxes.size()] = this->new_box(random, 0, 20);
            }
        }
        // Everyone out at once: aside at the next detection. A tenth: build, then two rebuilds
        // that served no kept detection, then aside. Forty a step: build, keep, rebuild, keep,
        // rebuild (the second short life), then aside.
        const std::vector<bool> expected =
            jumps < 0      ? std::vector<bool>{true, false, false, false, false, false, false, false}
            : jumps == 200 ? std::vector<bool>{true, true, true, false, false, false, false, false}
                           : std::vector<bool>{true, true, true, true, true, false, false, false};
        EXPECT_EQ(skinned, expected);
    }
}

TYPED_TEST(DetectorSkinTest, RejectsAnInvalidBoxByIndexAndStaysAsItWas) {
    using TestReal = typename TestFixture::Real;
    using TestBox = typename TestFixture::BoxT;
    Random random(11);
    std::vector<TestBox> boxes;
    for (int i = 0; i < 300; ++i) boxes.push_back(this->new_box(random, 0, 10));
    DetectorSettings settings;
    settings.skin = 0.3;
    Detector<TestReal, TestFixture::Dim> detector(settings);
    std::vector<Pair> before;
    detector.detect(boxes, before);
    detector.detect(boxes, before);
    std::vector<TestBox> broken = boxes;
    broken[42].max[0] = std::numeric_limits<TestReal>::quiet_NaN();
    std::vector<Pair> pairs;
    EXPECT_THROW(detector.detect(broken, pairs), InvalidBoxError);
    std::vector<Pair> after;
    const DetectStats stats = detector.detect(boxes, after);
    EXPECT_FALSE(stats.skin_rebuilt);
    EXPECT_EQ(after, before);
}

// A World has no skin to refuse: WorldSettings has none (tests/api/test_settings.cpp).
TEST(DetectorSkinSettings, RefusesANegativeOrNonFiniteSkin) {
    for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        DetectorSettings settings;
        settings.skin = bad;
        EXPECT_THROW(Detector3d{settings}, ArgumentError);
    }
}

// Double boxes held as floats: pairs closer than the floats resolve are settled on the doubles,
// on the kept path as on the rebuild.
TEST(DetectorSkinPrecision, SettlesOnTheDoublesWhatTheFloatsCannot) {
    DetectorSettings settings;
    settings.skin = 0.05;
    Detector3d detector(settings);
    const double gap = 1e-12;
    std::vector<Box3d> boxes;
    for (int i = 0; i < 200; ++i) {
        const double x = 3.0 * i;
        boxes.push_back(Box3d{{x, 0, 0}, {x + 1, 1, 1}});
        boxes.push_back(Box3d{{x + 1 + gap, 0, 0}, {x + 2, 1, 1}});
        boxes.push_back(Box3d{{x, 1, 0}, {x + 1, 2, 1}});
        boxes.push_back(Box3d{{x, 0, 1 + gap}, {x + 1, 1, 2}});
    }
    for (int step = 0; step < 3; ++step) {
        std::vector<Pair> pairs;
        const DetectStats stats = detector.detect(boxes, pairs);
        EXPECT_EQ(stats.skin_rebuilt, step == 0);
        EXPECT_GT(detector.last_retested_pairs(), 0U);
        sort_pairs(pairs);
        const std::vector<Pair> expected = brute_force_pairs<double, 3>(std::span<const Box3d>(boxes));
        EXPECT_EQ(pairs, expected);
        for (Box3d& box : boxes) {
            box.min[2] += 1e-13;  // a move the floats do not see
            box.max[2] += 1e-13;
        }
    }
}

}  // namespace
}  // namespace smb::test
