// SPDX-License-Identifier: MIT
// smb::Detector against brute force: seeded scenes of many kinds driven over many steps (motion,
// jumps, growing and shrinking arrays), the precision it chooses, and what it does with bad
// input and throwing sinks.

#include <gtest/gtest.h>

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

template <std::floating_point Real, int Dim>
std::vector<Pair> brute_force(const std::vector<Box<Real, Dim>>& boxes) {
    return brute_force_pairs<Real, Dim>(std::span<const Box<Real, Dim>>(boxes));
}

/// A kind of scene: where the boxes lie and how big they are.
struct SceneKind {
    std::string name;
    double centre = 0;         ///< the middle of the space on every axis
    double side = 1;           ///< typical box side
    double space = 20;         ///< side of the space the centres lie in
    double tiny_fraction = 0;  ///< share of boxes 1e-6 of `side` wide (points when `points`)
    bool points = false;
    double huge_fraction = 0;  ///< share of boxes as wide as the space
    /// Share of boxes 4 to 12 times `side` wide: wider than a few cells, so checked as oversized
    /// boxes by the cells they cover.
    double large_fraction = 0;
    bool lattice = false;  ///< unit boxes on an integer lattice: every neighbour touches
};

std::vector<SceneKind> scene_kinds() {
    return {
        {.name = "uniform"},
        {.name = "dense", .side = 2, .space = 12},
        {.name = "far", .centre = 1e6, .side = 1e-2, .space = 0.3},
        {.name = "very far", .centre = -3e12, .side = 5, .space = 150},
        {.name = "tiny and huge", .tiny_fraction = 0.3, .huge_fraction = 0.01},
        {.name = "a few large", .space = 25, .large_fraction = 0.04},
        {.name = "points", .tiny_fraction = 0.6, .points = true},
        {.name = "lattice", .space = 8, .lattice = true},
        {.name = "beyond float range", .centre = 1e300, .side = 1e298, .space = 1e300},
    };
}

template <typename T>
class DetectorTest : public ::testing::Test {
protected:
    using Real = typename T::real_type;
    static constexpr int Dim = T::dimension;
    using BoxT = Box<Real, Dim>;

    BoxT new_box(Random& random, const SceneKind& kind) {
        std::array<double, Dim> centre{};
        std::array<double, Dim> half{};
        const bool tiny = chance(random, kind.tiny_fraction);
        const bool huge = !tiny && chance(random, kind.huge_fraction);
        // Drawn only where asked for, so that the other kinds' scenes stay as they were.
        const bool large = !tiny && !huge && kind.large_fraction > 0 && chance(random, kind.large_fraction);
        for (int k = 0; k < Dim; ++k) {
            if (kind.lattice) {
                centre[k] = kind.centre + std::floor(uniform(random, 0, kind.space)) + 0.5;
                half[k] = 0.5;
                continue;
            }
            centre[k] = kind.centre + uniform(random, -0.5, 0.5) * kind.space;
            double side = kind.side * uniform(random, 0.5, 1.5);
            if (tiny) side = kind.points ? 0.0 : kind.side * 1e-6;
            if (huge) side = kind.space;
            if (large) side = kind.side * uniform(random, 4, 12);
            half[k] = 0.5 * side;
        }
        return box_around<Real, Dim>(centre, half);
    }

    BoxT moved(Random& random, const BoxT& box, const SceneKind& kind) {
        if (kind.lattice) return chance(random, 0.1) ? new_box(random, kind) : box;
        if (chance(random, 0.01)) return new_box(random, kind);
        const double shift = 0.01 * kind.side;
        BoxT next = box;
        for (int k = 0; k < Dim; ++k) {
            const double delta = uniform(random, -shift, shift);
            next.min[k] = static_cast<Real>(static_cast<double>(box.min[k]) + delta);
            next.max[k] = std::max(next.min[k], static_cast<Real>(static_cast<double>(box.max[k]) + delta));
        }
        return next;
    }

    void drive(const SceneKind& kind, std::uint64_t seed, const DetectorSettings& settings, int steps = 12) {
        SCOPED_TRACE(::testing::Message() << kind.name << ", seed " << seed << ", threads " << settings.threads);
        Random random(seed);
        DetectorSettings profiled = settings;
        profiled.profile = true;  // to see that the large boxes are checked as oversized ones
        Detector<Real, Dim> detector(profiled);
        std::size_t oversized = 0;
        std::vector<BoxT> boxes;
        for (int i = 0; i < 600; ++i) boxes.push_back(new_box(random, kind));
        for (int step = 0; step < steps; ++step) {
            SCOPED_TRACE(::testing::Message() << "step " << step);
            if (step > 0) {
                for (BoxT& box : boxes) box = moved(random, box, kind);
                if (step % 4 == 1) {
                    for (int i = 0; i < 90; ++i) boxes.push_back(new_box(random, kind));
                } else if (step % 4 == 3) {
                    boxes.resize(boxes.size() - 120);
                }
            }
            std::vector<Pair> pairs;
            const DetectStats stats = detector.detect(boxes, pairs);
            oversized += detector.last_profile().oversized_boxes;
            EXPECT_EQ(stats.pairs, pairs.size());
            EXPECT_EQ(stats.boxes, boxes.size());
            const std::vector<BoxT>& shown = boxes;
            EXPECT_TRUE(same_pairs(pairs, brute_force_pairs<Real, Dim>(boxes),
                                   [&shown](BoxId id) { return describe(shown.at(id)); }));
            if (::testing::Test::HasFailure()) return;
        }
        if (kind.large_fraction > 0) {
            EXPECT_GT(oversized, 0U);
        }
    }
};

TYPED_TEST_SUITE(DetectorTest, Shapes, ShapeNames);

TYPED_TEST(DetectorTest, MatchesBruteForceOnEveryKindOfSceneOverManySteps) {
    for (const SceneKind& kind : scene_kinds()) {
        if (std::is_same_v<typename TestFixture::Real, float> && std::abs(kind.centre) > 1e30) continue;
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            this->drive(kind, seed, DetectorSettings{});
            DetectorSettings small_cells;
            small_cells.target_cell_population = 3;
            small_cells.threads = 3;
            this->drive(kind, seed + 100, small_cells);
        }
    }
}

TYPED_TEST(DetectorTest, ReportsTheSamePairsInTheSameOrderWhateverTheThreadCount) {
    using TestBox = typename TestFixture::BoxT;
    Random random(7);
    const SceneKind kind{.name = "dense", .side = 2, .space = 12};
    std::vector<TestBox> boxes;
    for (int i = 0; i < 2000; ++i) boxes.push_back(this->new_box(random, kind));
    std::vector<std::vector<Pair>> runs;
    for (std::size_t threads : {1U, 2U, 4U}) {
        DetectorSettings settings;
        settings.threads = threads;
        settings.target_cell_population = 6;
        Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
        std::vector<Pair> pairs;
        detector.detect(boxes, pairs);
        detector.detect(boxes, pairs);
        runs.push_back(pairs);
    }
    EXPECT_EQ(runs[0], runs[1]);
    EXPECT_EQ(runs[0], runs[2]);
}

TYPED_TEST(DetectorTest, RejectsAnInvalidBoxByIndexAndStaysAsItWas) {
    using TestReal = typename TestFixture::Real;
    using TestBox = typename TestFixture::BoxT;
    Random random(11);
    const SceneKind kind{.name = "uniform"};
    std::vector<TestBox> boxes;
    for (int i = 0; i < 300; ++i) boxes.push_back(this->new_box(random, kind));
    Detector<TestReal, TestFixture::Dim> detector;
    std::vector<Pair> first;
    detector.detect(boxes, first);
    // From the second detection on, a detection without changes repeats its list, order included.
    std::vector<Pair> before;
    detector.detect(boxes, before);
    sort_pairs(first);
    EXPECT_TRUE(same_pairs(before, first));
    const std::size_t bytes = detector.bytes_held();
    const TestReal nan = std::numeric_limits<TestReal>::quiet_NaN();
    const TestReal inf = std::numeric_limits<TestReal>::infinity();
    for (int bad = 0; bad < 4; ++bad) {
        std::vector<TestBox> broken = boxes;
        TestBox& box = broken[137];
        if (bad == 0) box.min[1] = nan;
        if (bad == 1) box.max[0] = inf;
        if (bad == 2) box.min[0] = -inf;
        if (bad == 3) std::swap(box.min[TestFixture::Dim - 1], box.max[TestFixture::Dim - 1]);
        if (bad == 3 && box.min == box.max) box.min[0] = box.max[0] + 1;
        std::vector<Pair> pairs{Pair{1, 2}};
        try {
            detector.detect(broken, pairs);
            ADD_FAILURE() << "no error for bad box " << bad;
        } catch (const InvalidBoxError& error) {
            EXPECT_NE(std::string(error.what()).find("box 137"), std::string::npos) << error.what();
        }
        EXPECT_EQ(pairs, (std::vector<Pair>{Pair{1, 2}})) << "the caller's pairs are as they were";
        EXPECT_EQ(detector.bytes_held(), bytes);
    }
    std::vector<Pair> after;
    detector.detect(boxes, after);
    EXPECT_EQ(after, before);
}

TYPED_TEST(DetectorTest, HandlesNoBoxesOneBoxAndClear) {
    using TestBox = typename TestFixture::BoxT;
    Detector<typename TestFixture::Real, TestFixture::Dim> detector;
    std::vector<Pair> pairs{Pair{1, 2}};
    EXPECT_EQ(detector.detect(std::span<const TestBox>{}, pairs).pairs, 0U);
    EXPECT_TRUE(pairs.empty());
    EXPECT_EQ(detector.last_precision(), HeldPrecision::none);
    std::vector<TestBox> boxes(1);
    detector.detect(boxes, pairs);
    EXPECT_TRUE(pairs.empty());
    boxes.resize(3);  // three identical zero-size boxes at the origin: all touch
    detector.detect(boxes, pairs);
    EXPECT_EQ(pairs, (std::vector<Pair>{{0, 1}, {0, 2}, {1, 2}}));
    detector.detect(std::span<const TestBox>{}, pairs);
    EXPECT_TRUE(pairs.empty());
    detector.detect(boxes, pairs);
    EXPECT_EQ(pairs.size(), 3U);
    detector.clear();
    EXPECT_LT(detector.bytes_held(), 4096U);
    detector.detect(boxes, pairs);
    EXPECT_EQ(pairs.size(), 3U);
}

TYPED_TEST(DetectorTest, AThrowingSinkLeavesItValid) {
    using TestBox = typename TestFixture::BoxT;
    Random random(5);
    const SceneKind kind{.name = "dense", .side = 2, .space = 12};
    std::vector<TestBox> boxes;
    for (int i = 0; i < 1500; ++i) boxes.push_back(this->new_box(random, kind));
    for (std::size_t threads : {1U, 3U}) {
        DetectorSettings settings;
        settings.threads = threads;
        settings.pair_chunk_size = 64;
        Detector<typename TestFixture::Real, TestFixture::Dim> detector(settings);
        int chunks = 0;
        EXPECT_THROW(detector.detect(boxes,
                                     [&chunks](std::span<const Pair>) {
                                         if (++chunks == 3) throw std::runtime_error("sink full");
                                     }),
                     std::runtime_error);
        std::vector<Pair> pairs;
        detector.detect(boxes, pairs);
        sort_pairs(pairs);
        EXPECT_EQ(pairs, brute_force(boxes));
    }
}

// The first detection cuts every group, the threads side by side: its phases must still be
// shares of the call's wall time (their seconds of cutting, summed, once came out above it).
TEST(DetectorStats, PhasesAreSharesOfTheCallOnSeveralThreads) {
    Random random(5);
    std::vector<Box3d> boxes;
    for (int i = 0; i < 100000; ++i) {
        const double x = uniform(random, 0, 100), y = uniform(random, 0, 100), z = uniform(random, 0, 100);
        boxes.push_back(Box3d{{x, y, z}, {x + 1, y + 1, z + 1}});
    }
    for (const std::size_t threads : {1U, 2U, 4U}) {
        DetectorSettings settings;
        settings.threads = threads;
        settings.profile = true;
        Detector3d detector(settings);
        std::vector<Pair> pairs;
        const double total_seconds = detector.detect(boxes, pairs).total_seconds;
        const DetectProfile& first = detector.last_profile();
        EXPECT_GE(first.scan_seconds, 0.0);
        EXPECT_GE(first.quantile_seconds, 0.0);
        EXPECT_GE(first.cut_regroup_seconds, 0.0) << threads << " thread(s)";
        EXPECT_GE(first.check_seconds, 0.0);
        EXPECT_LE(first.scan_seconds + first.quantile_seconds + first.cut_regroup_seconds + first.check_seconds,
                  total_seconds)
            << threads << " thread(s)";
    }
}

// The copy's and the levels' seconds split the two phases they come from: never negative, never
// more than those phases together, one level per axis (the third zero in 2D), on the build and
// on a warm step, on one thread and on two.
template <int Dim>
void expect_levels_within_their_phases(std::size_t threads) {
    Random random(6);
    std::vector<Box<double, Dim>> boxes;
    for (int i = 0; i < 50000; ++i) {
        Box<double, Dim> box;
        for (int k = 0; k < Dim; ++k) {
            box.min[k] = uniform(random, 0, 60);
            box.max[k] = box.min[k] + 1;
        }
        boxes.push_back(box);
    }
    DetectorSettings settings;
    settings.threads = threads;
    settings.profile = true;
    Detector<double, Dim> detector(settings);
    std::vector<Pair> pairs;
    for (int step = 0; step < 2; ++step) {
        SCOPED_TRACE(::testing::Message() << Dim << "D, " << threads << " thread(s), step " << step);
        detector.detect(boxes, pairs);
        const DetectProfile& stats = detector.last_profile();
        double split = stats.copy_seconds;
        EXPECT_GE(stats.copy_seconds, 0.0);
        for (std::size_t level = 0; level < stats.level_seconds.size(); ++level) {
            if (level < static_cast<std::size_t>(Dim)) {
                EXPECT_GT(stats.level_seconds[level], 0.0) << "level " << level;
            } else {
                EXPECT_EQ(stats.level_seconds[level], 0.0) << "level " << level;
            }
            split += stats.level_seconds[level];
        }
        EXPECT_LE(split, stats.quantile_seconds + stats.cut_regroup_seconds + 1e-9);
        for (Box<double, Dim>& box : boxes) {
            box.min[0] += 0.01;
            box.max[0] += 0.01;
        }
    }
}

TEST(DetectorStats, LevelsSplitTheirPhases) {
    for (const std::size_t threads : {1U, 2U}) {
        expect_levels_within_their_phases<2>(threads);
        expect_levels_within_their_phases<3>(threads);
    }
}

// The paper's pipeline has no copy and no levels of kept cuts: it leaves them zero.
TEST(DetectorStats, PaperPipelineLeavesTheLevelsZero) {
    WorldSettings paper;
    paper.pipeline = Pipeline::paper_lists;
    paper.profile = true;
    World3d world(paper);
    for (BoxId id = 0; id < 1000; ++id) {
        const double x = static_cast<double>(id % 10), y = static_cast<double>(id / 10 % 10),
                     z = static_cast<double>(id / 100);
        world.insert(id, Box3d{{x, y, z}, {x + 1.5, y + 1.5, z + 1.5}});
    }
    std::vector<Pair> pairs;
    world.detect(pairs);
    const DetectProfile& stats = world.last_profile();
    EXPECT_FALSE(pairs.empty());
    EXPECT_GT(stats.list_sort_seconds, 0.0);
    EXPECT_EQ(stats.copy_seconds, 0.0);
    for (const double seconds : stats.level_seconds) EXPECT_EQ(seconds, 0.0);
}

TEST(DetectorSettings, RefusesBadSettings) {
    DetectorSettings empty_cells;
    empty_cells.target_cell_population = 0;
    EXPECT_THROW(Detector3d{empty_cells}, ArgumentError);
    Detector3d detector;
    std::vector<Box3d> boxes(2);
    EXPECT_THROW(detector.detect(boxes, PairSink{}), ArgumentError);
}

TEST(DetectorSettings, RefusesToHoldMorePairsThanAllowedAndStreamsThemInstead) {
    DetectorSettings settings;
    settings.max_pairs_held = 100;
    Detector3f detector(settings);
    const std::vector<Box3f> same(200, Box3f{{0, 0, 0}, {1, 1, 1}});  // 19 900 pairs
    std::vector<Pair> pairs;
    EXPECT_THROW(detector.detect(same, pairs), PairLimitError);
    EXPECT_EQ(pairs.capacity(), 0U);
    std::size_t streamed = 0;
    detector.detect(same, [&streamed](std::span<const Pair> chunk) { streamed += chunk.size(); });
    EXPECT_EQ(streamed, 19900U);
}

// Double boxes held as floats: pairs closer than the floats resolve are settled on the doubles.
TEST(DetectorPrecision, SettlesOnTheDoublesWhatTheFloatsCannot) {
    Detector3d detector;
    const double gap = 1e-12;
    std::vector<Box3d> boxes;
    for (int i = 0; i < 200; ++i) {
        const double x = 3.0 * i;
        boxes.push_back(Box3d{{x, 0, 0}, {x + 1, 1, 1}});
        // Apart by 1e-12 on x (floats cannot tell), touching on y (exact), apart on z by a gap.
        boxes.push_back(Box3d{{x + 1 + gap, 0, 0}, {x + 2, 1, 1}});
        boxes.push_back(Box3d{{x, 1, 0}, {x + 1, 2, 1}});
        boxes.push_back(Box3d{{x, 0, 1 + gap}, {x + 1, 1, 2}});
    }
    std::vector<Pair> pairs;
    detector.detect(boxes, pairs);
    EXPECT_EQ(detector.last_precision(), HeldPrecision::floats);
    EXPECT_GT(detector.last_retested_pairs(), 0U);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, brute_force(boxes));
}

// The same pairs spread over a lattice, so that the cells stay small and are checked pair by
// pair, where the floats' overlaps by a margin are reported without a second test: a pair
// within the floats' resolution must still reach the doubles, on one thread and on two.
TEST(DetectorPrecision, SettlesOnTheDoublesWhatTheFloatsCannotInSmallCells) {
    const std::vector<Box3d> boxes = near_touching_lattice(10);
    const std::vector<Pair> expected = brute_force(boxes);
    for (const std::size_t threads : {1U, 2U}) {
        DetectorSettings settings;
        settings.threads = threads;
        Detector3d detector(settings);
        std::vector<Pair> pairs;
        detector.detect(boxes, pairs);
        EXPECT_EQ(detector.last_precision(), HeldPrecision::floats);
        EXPECT_GT(detector.last_retested_pairs(), 0U);
        sort_pairs(pairs);
        EXPECT_EQ(pairs, expected) << threads << " thread(s)";
    }
}

TEST(DetectorPrecision, HoldsDoublesWhereFloatsWouldNotResolveTheScene) {
    Random random(3);
    std::vector<Box3d> points;
    for (int i = 0; i < 1000; ++i) {
        const double x = uniform(random, 0, 100), y = uniform(random, 0, 100), z = uniform(random, 0, 100);
        points.push_back(Box3d{{x, y, z}, {x, y, z}});
    }
    Detector3d detector;
    std::vector<Pair> pairs;
    detector.detect(points, pairs);
    EXPECT_EQ(detector.last_precision(), HeldPrecision::doubles);
    EXPECT_TRUE(pairs.empty());

    // Turned into boxes, the same scene is held as floats once judged again (within 64
    // detections); far beyond float range, as doubles at once (the scene left its region).
    for (Box3d& box : points) {
        for (int k = 0; k < 3; ++k) box.max[k] += 2;
    }
    for (int again = 0; again < 64; ++again) detector.detect(points, pairs);
    EXPECT_EQ(detector.last_precision(), HeldPrecision::floats);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, brute_force(points));
    for (Box3d& box : points) {
        for (int k = 0; k < 3; ++k) {
            box.min[k] *= 1e300;
            box.max[k] *= 1e300;
        }
    }
    detector.detect(points, pairs);
    EXPECT_EQ(detector.last_precision(), HeldPrecision::doubles);
    sort_pairs(pairs);
    EXPECT_EQ(pairs, brute_force(points));
}

TEST(DetectorPrecision, FollowsASceneThatDriftsFarFromWhereItStarted) {
    Random random(9);
    std::vector<Box3d> boxes;
    for (int i = 0; i < 800; ++i) {
        const std::array<double, 3> centre{uniform(random, 0, 20), uniform(random, 0, 20), uniform(random, 0, 20)};
        boxes.push_back(box_around<double, 3>(centre, {0.5, 0.5, 0.5}));
    }
    Detector3d detector;
    for (int step = 0; step < 12; ++step) {
        SCOPED_TRACE(step);
        std::vector<Pair> pairs;
        detector.detect(boxes, pairs);
        EXPECT_EQ(detector.last_precision(), HeldPrecision::floats);
        sort_pairs(pairs);
        EXPECT_EQ(pairs, brute_force(boxes));
        for (Box3d& box : boxes) {
            for (int k = 0; k < 3; ++k) {
                box.min[k] = box.min[k] * 10 + 1e4;
                box.max[k] = box.max[k] * 10 + 1e4;
            }
        }
    }
}

}  // namespace
}  // namespace smb::test
