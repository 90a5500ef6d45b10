// SPDX-License-Identifier: MIT
// The distributed detector's pairs, gathered from every rank, against brute force over the whole
// scene: each pair once (or once on each holder), on the rank the hand-off names.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "mpi/mpi_scene.hpp"
#include "smb/mpi/distributed_detector.hpp"

namespace smb::mpi::test {
namespace {

#ifdef SMB_TEST_REDUCED
constexpr int scene_boxes = 200;
constexpr int steps = 8;
#else
constexpr int scene_boxes = 500;
constexpr int steps = 12;
#endif

template <class DetectorT>
class DistributedDetection : public ::testing::Test {};

using DetectorTypes =
    ::testing::Types<DistributedDetector3d, DistributedDetector3f, DistributedDetector2f, DistributedDetector2d>;
TYPED_TEST_SUITE(DistributedDetection, DetectorTypes);

/// Runs one step and checks every rank's pairs against brute force: the union is exact, each
/// pair sits on the rank(s) the hand-off names, and nowhere else.
/// `reversed`: each rank passes its boxes in the reverse order of the scene's.
template <class DetectorT, class BoxT>
void expect_exact_step(DetectorT& detector, const Scene<BoxT>& scene, PairHandOff hand_off, bool reversed = false) {
    std::vector<BoxId> ids;
    std::vector<BoxT> boxes;
    scene.share_of(rank_of(), ids, boxes);
    if (reversed) {
        std::reverse(ids.begin(), ids.end());
        std::reverse(boxes.begin(), boxes.end());
    }
    std::vector<Pair> pairs;
    detector.detect(ids, boxes, pairs);
    const std::vector<RankedPair> found = gather_pairs(pairs);
    std::vector<RankedPair> expected;
    for (const Pair& pair : brute_force_pairs(scene)) {
        const int first = scene.holder_of(pair.a), second = scene.holder_of(pair.b);
        expected.push_back({pair, first});
        if (hand_off == PairHandOff::both_holders && second != first) expected.push_back({pair, second});
    }
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(found.size(), expected.size());
    EXPECT_TRUE(found == expected);
}

/// A random scene: small boxes, a few large ones, and huge ones that span every region.
template <class BoxT>
Scene<BoxT> random_scene(std::mt19937_64& engine, int count, int ranks) {
    Scene<BoxT> scene;
    std::uniform_int_distribution<int> holder(0, ranks - 1);
    std::set<BoxId> used;
    for (int i = 0; i < count; ++i) {
        BoxId id = 0;
        do {
            id = engine() >> (engine() % 64);  // small and large ids both
        } while (!used.insert(id).second);
        scene.ids.push_back(id);
        const double size = i % 97 == 0 ? 2.0 : (i % 13 == 0 ? 0.3 : 0.04);
        BoxT box = random_box<BoxT>(engine, size);
        if (i % 97 == 0) {  // huge: from below the scene to above it
            for (int k = 0; k < BoxT::dimension; ++k) box.min[k] = -1, box.max[k] = 2;
        }
        scene.boxes.push_back(box);
        scene.holders.push_back(holder(engine));
    }
    return scene;
}

/// Small motions of every box, a few teleports, removals and insertions, and some boxes that
/// move to another rank.
template <class BoxT>
void advance(Scene<BoxT>& scene, std::mt19937_64& engine, int ranks) {
    using Real = typename BoxT::real_type;
    std::uniform_real_distribution<double> step(-0.01, 0.01);
    std::uniform_int_distribution<int> percent(0, 99);
    std::uniform_int_distribution<int> holder(0, ranks - 1);
    for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
        BoxT& box = scene.boxes[i];
        const int roll = percent(engine);
        if (roll < 3) {
            box = random_box<BoxT>(engine, 0.05);  // a teleport
        } else {
            for (int k = 0; k < BoxT::dimension; ++k) {
                const Real shift = static_cast<Real>(step(engine));
                box.min[k] += shift;
                box.max[k] += shift;
            }
        }
        if (roll >= 97) scene.holders[i] = holder(engine);  // migrates to another rank
    }
    for (int r = 0; r < 5 && !scene.ids.empty(); ++r) {  // removals
        const std::size_t at = engine() % scene.ids.size();
        scene.ids.erase(scene.ids.begin() + static_cast<std::ptrdiff_t>(at));
        scene.boxes.erase(scene.boxes.begin() + static_cast<std::ptrdiff_t>(at));
        scene.holders.erase(scene.holders.begin() + static_cast<std::ptrdiff_t>(at));
    }
    for (int r = 0; r < 5; ++r) {  // insertions, under ids never used (the top bit set)
        scene.ids.push_back((BoxId{1} << 63) | engine() % (BoxId{1} << 40));
        if (std::find(scene.ids.begin(), scene.ids.end() - 1, scene.ids.back()) != scene.ids.end() - 1) {
            scene.ids.pop_back();
            continue;
        }
        scene.boxes.push_back(random_box<BoxT>(engine, 0.05));
        scene.holders.push_back(holder(engine));
    }
}

TYPED_TEST(DistributedDetection, RandomScenesOverManySteps) {
    using BoxT = typename TypeParam::box_type;
    for (PairHandOff hand_off : {PairHandOff::smaller_id_holder, PairHandOff::both_holders}) {
        std::mt19937_64 engine(2026);
        Scene<BoxT> scene = random_scene<BoxT>(engine, scene_boxes, ranks_of());
        DistributedSettings settings;
        settings.hand_off = hand_off;
        TypeParam detector(MPI_COMM_WORLD, settings);
        int recuts = 0;
        for (int step = 0; step < steps; ++step) {
            SCOPED_TRACE(step);
            expect_exact_step(detector, scene, hand_off);
            recuts += detector.last_stats().recut ? 1 : 0;
            advance(scene, engine, ranks_of());
        }
        // The first step cuts; one region (one rank) is all of space and is never cut.
        if (ranks_of() == 1) {
            EXPECT_EQ(recuts, 0);
        } else {
            EXPECT_GE(recuts, 1);
        }
    }
}

/// Most boxes stay still; a few move a little (some across a plane), teleport, pass to another
/// rank with or without moving, vanish or appear: what the exchange of changes must follow.
template <class BoxT>
void advance_sparsely(Scene<BoxT>& scene, std::mt19937_64& engine, int ranks) {
    using Real = typename BoxT::real_type;
    std::uniform_real_distribution<double> step(-0.05, 0.05);
    std::uniform_int_distribution<int> percent(0, 99);
    std::uniform_int_distribution<int> holder(0, ranks - 1);
    for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
        BoxT& box = scene.boxes[i];
        const int roll = percent(engine);
        if (roll < 85) continue;
        if (roll < 92 || roll >= 98) {
            for (int k = 0; k < BoxT::dimension; ++k) {
                const Real shift = static_cast<Real>(step(engine));
                box.min[k] += shift;
                box.max[k] += shift;
            }
        } else if (roll < 95) {
            box = random_box<BoxT>(engine, 0.05);
        }
        if (roll >= 95) scene.holders[i] = holder(engine);
    }
    for (int r = 0; r < 3 && !scene.ids.empty(); ++r) {
        const std::size_t at = engine() % scene.ids.size();
        scene.ids.erase(scene.ids.begin() + static_cast<std::ptrdiff_t>(at));
        scene.boxes.erase(scene.boxes.begin() + static_cast<std::ptrdiff_t>(at));
        scene.holders.erase(scene.holders.begin() + static_cast<std::ptrdiff_t>(at));
    }
    for (int r = 0; r < 3; ++r) {
        const BoxId id = (BoxId{1} << 62) | engine() % (BoxId{1} << 40);
        if (scene.holder_of(id) >= 0) continue;
        scene.ids.push_back(id);
        scene.boxes.push_back(random_box<BoxT>(engine, 0.05));
        scene.holders.push_back(holder(engine));
    }
}

/// The bytes of boxes and of ids that all ranks sent at the last step.
template <class DetectorT>
std::array<unsigned long long, 2> bytes_sent_by_all(const DetectorT& detector) {
    std::array<unsigned long long, 2> bytes = {detector.last_stats().box_bytes_sent,
                                               detector.last_stats().id_bytes_sent};
    MPI_Allreduce(MPI_IN_PLACE, bytes.data(), 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    return bytes;
}

TYPED_TEST(DistributedDetection, MostBoxesStillOnlyTheChangesTravel) {
    using BoxT = typename TypeParam::box_type;
    for (PairHandOff hand_off : {PairHandOff::smaller_id_holder, PairHandOff::both_holders}) {
        std::mt19937_64 engine(99);
        Scene<BoxT> scene = random_scene<BoxT>(engine, scene_boxes, ranks_of());
        DistributedSettings settings;
        settings.hand_off = hand_off;
        TypeParam detector(MPI_COMM_WORLD, settings);
        expect_exact_step(detector, scene, hand_off);
        const auto first = bytes_sent_by_all(detector);
        for (int step = 1; step < steps; ++step) {
            SCOPED_TRACE(step);
            advance_sparsely(scene, engine, ranks_of());
            expect_exact_step(detector, scene, hand_off, step % 3 == 0);
            const auto bytes = bytes_sent_by_all(detector);
            if (ranks_of() > 1 && !detector.last_stats().recut) {
                EXPECT_LT(bytes[0], first[0] / 2);
                EXPECT_LT(bytes[1], first[1] / 2);
            }
        }
        // Nothing changed, in another order: nothing travels but the pairs.
        expect_exact_step(detector, scene, hand_off, true);
        if (!detector.last_stats().recut) {
            EXPECT_EQ(bytes_sent_by_all(detector), (std::array<unsigned long long, 2>{0, 0}));
        }
    }
}

TYPED_TEST(DistributedDetection, IdsAtTheEdgesOfTheRange) {
    // Where ids are hashed, packed or narrowed, the edges show: 2^32 next to 2^32 - 1, ids that
    // differ only above bit 32, the top bit, 2^64 - 1. Their boxes overlap one another.
    using BoxT = typename TypeParam::box_type;
    constexpr BoxId top = std::numeric_limits<BoxId>::max();
    const std::vector<BoxId> edges = {0,
                                      1,
                                      7,
                                      BoxId{1} << 31,
                                      (BoxId{1} << 32) - 1,
                                      BoxId{1} << 32,
                                      (BoxId{1} << 32) + 1,
                                      (BoxId{1} << 32) + 7,
                                      (BoxId{1} << 63) - 1,
                                      BoxId{1} << 63,
                                      (BoxId{1} << 63) + 1,
                                      top - 1,
                                      top};
    for (PairHandOff hand_off : {PairHandOff::smaller_id_holder, PairHandOff::both_holders}) {
        std::mt19937_64 engine(35);
        Scene<BoxT> scene = random_scene<BoxT>(engine, scene_boxes, ranks_of());
        std::set<BoxId> used(edges.begin(), edges.end());
        for (std::size_t i = 0; i < scene.ids.size(); ++i) {
            if (i < edges.size()) {
                scene.ids[i] = edges[i];
                scene.boxes[i] = random_box<BoxT>(engine, 0.0);
                for (int k = 0; k < BoxT::dimension; ++k) scene.boxes[i].min[k] = 0.5f, scene.boxes[i].max[k] = 0.5f;
                continue;
            }
            while (!used.insert(scene.ids[i]).second) scene.ids[i] = engine();
        }
        DistributedSettings settings;
        settings.hand_off = hand_off;
        TypeParam detector(MPI_COMM_WORLD, settings);
        for (int step = 0; step < 4; ++step) {
            SCOPED_TRACE(step);
            expect_exact_step(detector, scene, hand_off, step % 2 == 1);
            advance(scene, engine, ranks_of());
        }
    }
}

TYPED_TEST(DistributedDetection, AllBoxesOnOneRankOthersEmpty) {
    using BoxT = typename TypeParam::box_type;
    for (int holder : {0, ranks_of() - 1}) {
        std::mt19937_64 engine(7);
        Scene<BoxT> scene = random_scene<BoxT>(engine, scene_boxes, 1);
        std::fill(scene.holders.begin(), scene.holders.end(), holder);
        TypeParam detector(MPI_COMM_WORLD);
        expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
        advance(scene, engine, 1);
        std::fill(scene.holders.begin(), scene.holders.end(), holder);
        expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
    }
}

TYPED_TEST(DistributedDetection, NoBoxesAnywhere) {
    using BoxT = typename TypeParam::box_type;
    TypeParam detector(MPI_COMM_WORLD);
    Scene<BoxT> scene;
    expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
    expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
}

TYPED_TEST(DistributedDetection, IdenticalBoxesAndHugeBoxesOnly) {
    using BoxT = typename TypeParam::box_type;
    Scene<BoxT> scene;
    for (int i = 0; i < 60; ++i) {
        BoxT box;
        for (int k = 0; k < BoxT::dimension; ++k) {
            box.min[k] = i < 40 ? 0.5f : -10.0f;  // 40 identical boxes: their centres tie at every cut
            box.max[k] = i < 40 ? 0.5f : 10.0f;
        }
        scene.ids.push_back(static_cast<BoxId>(1000 - i));
        scene.boxes.push_back(box);
        scene.holders.push_back(i % ranks_of());
    }
    TypeParam detector(MPI_COMM_WORLD);
    expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
    expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);  // the same cuts again
}

/// Every plane of every rank's region, on every axis, gathered on all ranks.
template <int Dim>
std::vector<std::vector<double>> all_planes(const Box<double, Dim>& mine) {
    std::vector<double> faces(2 * Dim);
    for (int k = 0; k < Dim; ++k) faces[2 * k] = mine.min[k], faces[2 * k + 1] = mine.max[k];
    std::vector<double> all(faces.size() * static_cast<std::size_t>(ranks_of()));
    MPI_Allgather(faces.data(), 2 * Dim, MPI_DOUBLE, all.data(), 2 * Dim, MPI_DOUBLE, MPI_COMM_WORLD);
    std::vector<std::vector<double>> planes(Dim);
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (std::isfinite(all[i])) planes[(i % (2 * Dim)) / 2].push_back(all[i]);
    }
    return planes;
}

TYPED_TEST(DistributedDetection, BoxesExactlyOnTheCutPlanes) {
    using BoxT = typename TypeParam::box_type;
    using Real = typename BoxT::real_type;
    constexpr int dim = BoxT::dimension;
    std::mt19937_64 engine(11);
    Scene<BoxT> scene = random_scene<BoxT>(engine, scene_boxes, ranks_of());
    DistributedSettings settings;
    settings.rebalance_threshold = 1e9;  // keep the first step's planes for the boxes put on them
    TypeParam detector(MPI_COMM_WORLD, settings);
    expect_exact_step(detector, scene, PairHandOff::smaller_id_holder);
    const auto planes = all_planes<dim>(detector.region());
    // On each plane: boxes ending on it from below, starting on it from above, flat on it, and
    // pairs whose intersection's lower corner is a point where two planes meet.
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    BoxId next_id = 0;
    std::vector<double> points_on_axis[dim];
    for (int k = 0; k < dim; ++k) {
        points_on_axis[k] = planes[k];
        points_on_axis[k].push_back(0.5);
    }
    for (int k = 0; k < dim; ++k) {
        for (double plane : planes[k]) {
            const auto c = static_cast<Real>(plane);
            for (int shape = 0; shape < 4; ++shape) {
                BoxT box;
                for (int j = 0; j < dim; ++j) {
                    const auto& candidates = points_on_axis[j];
                    const auto at = static_cast<Real>(candidates[engine() % candidates.size()]);
                    box.min[j] = at - static_cast<Real>(0.01 * unit(engine)) * (j % 2 == 0 ? 1 : 0);
                    box.max[j] = at;
                }
                if (shape == 0) box.min[k] = c - Real(0.02), box.max[k] = c;  // ends on the plane
                if (shape == 1) box.min[k] = c, box.max[k] = c + Real(0.02);  // starts on it
                if (shape == 2) box.min[k] = c, box.max[k] = c;               // flat on it
                if (shape == 3) box.min[k] = c - Real(0.5), box.max[k] = c + Real(0.5);
                do {
                    ++next_id;  // past every id of the random scene
                } while (scene.holder_of(next_id) >= 0);
                scene.ids.push_back(next_id);
                scene.boxes.push_back(box);
                scene.holders.push_back(static_cast<int>(engine() % static_cast<unsigned>(ranks_of())));
            }
        }
    }
    for (PairHandOff hand_off : {PairHandOff::smaller_id_holder}) {
        expect_exact_step(detector, scene, hand_off);
        EXPECT_FALSE(detector.last_stats().recut);
    }
}

TEST(DistributedRegions, FactorTheRanksOverTheAxes) {
    DistributedDetector3d detector(MPI_COMM_WORLD);
    const std::vector<int> per_axis = detector.regions_per_axis();
    ASSERT_EQ(per_axis.size(), 3u);
    EXPECT_EQ(per_axis[0] * per_axis[1] * per_axis[2], ranks_of());
    EXPECT_GE(per_axis[0], per_axis[2]);  // the largest factors go to the first axes
}

TEST(DistributedRegions, EqualPopulationAfterTheCut) {
    // 400 boxes per rank, all dealt to rank 0 so that the distribution says nothing of space:
    // after the cut, each region owns close to 400.
    std::mt19937_64 engine(5);
    Scene<Box3d> scene = random_scene<Box3d>(engine, 400 * ranks_of(), 1);
    DistributedDetector3d detector(MPI_COMM_WORLD);
    std::vector<BoxId> ids;
    std::vector<Box3d> boxes;
    scene.share_of(rank_of(), ids, boxes);
    std::vector<Pair> pairs;
    detector.detect(ids, boxes, pairs);
    EXPECT_EQ(detector.last_stats().recut, ranks_of() > 1);
    EXPECT_NEAR(static_cast<double>(detector.last_stats().boxes_owned), 400.0, 40.0);
}

}  // namespace
}  // namespace smb::mpi::test
