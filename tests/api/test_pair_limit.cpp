// SPDX-License-Identifier: MIT
// Pair explosions: detect(vector) refuses to hold more than max_pairs_held pairs, detect(sink)
// streams any number, and a sink that throws leaves the world valid.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "reference/brute_force.hpp"
#include "smb/smb.hpp"

namespace smb {
namespace {

std::vector<Box3d> identical_boxes(std::size_t n) { return std::vector<Box3d>(n, Box3d{{0, 0, 0}, {1, 1, 1}}); }

TEST(PairLimit, VectorDetectionThrowsPastTheLimitAndSinkStreams) {
    WorldSettings settings;
    settings.max_pairs_held = 1000;
    settings.pair_chunk_size = 64;
    World3d world(settings);
    world.assign(identical_boxes(300));  // 300 * 299 / 2 = 44 850 pairs
    std::vector<Pair> pairs;
    EXPECT_THROW(world.detect(pairs), PairLimitError);
    EXPECT_TRUE(pairs.empty()) << "no partial list that looks complete";
    EXPECT_EQ(pairs.capacity(), 0U) << "the refused pairs' memory is given back";

    std::size_t streamed = 0;
    std::size_t largest_chunk = 0;
    const DetectStats stats = world.detect([&](std::span<const Pair> chunk) {
        streamed += chunk.size();
        largest_chunk = std::max(largest_chunk, chunk.size());
        for (const Pair& pair : chunk) ASSERT_LT(pair.a, pair.b);
    });
    EXPECT_EQ(streamed, 44850U);
    EXPECT_EQ(stats.pairs, 44850U);
    EXPECT_LE(largest_chunk, 64U);
}

// The pairs go straight into the caller's vector, room after room: the limit holds at its exact
// count, whatever the room, the thread count or the pairs the vector held before.
TEST(PairLimit, VectorDetectionHoldsExactlyTheLimitAndKeepsOldPairsWhenRefused) {
    const std::vector<Box3d> boxes = identical_boxes(150);  // 11 175 pairs: rooms of 4096 and a part
    const std::vector<Pair> before{{1, 2}, {3, 4}, {5, 6}};
    const auto expected = test::brute_force_pairs<double, 3>(std::span<const Box3d>(boxes));
    for (const std::size_t threads : {1U, 2U}) {
        for (const std::size_t limit : {11175U, 11174U, 4096U, 4095U, 0U}) {
            DetectorSettings settings;
            settings.threads = threads;
            settings.max_pairs_held = limit;
            Detector3d detector(settings);
            std::vector<Pair> pairs = before;
            if (limit >= 11175U) {
                const DetectStats stats = detector.detect(boxes, pairs);
                EXPECT_EQ(stats.pairs, 11175U);
                sort_pairs(pairs);
                EXPECT_EQ(pairs, expected);
            } else {
                EXPECT_THROW(detector.detect(boxes, pairs), PairLimitError) << limit << ", " << threads << " threads";
                EXPECT_EQ(pairs, before) << "the old pairs stay when the new ones are refused";
            }
            WorldSettings world_settings;
            world_settings.threads = threads;
            world_settings.max_pairs_held = limit;
            World3d world(world_settings);
            world.assign(boxes);
            pairs = before;
            if (limit >= 11175U) {
                EXPECT_EQ(world.detect(pairs).pairs, 11175U);
                sort_pairs(pairs);
                EXPECT_EQ(pairs, expected);
            } else {
                EXPECT_THROW(world.detect(pairs), PairLimitError) << limit << ", " << threads << " threads";
                EXPECT_EQ(pairs, before);
            }
        }
    }
}

TEST(PairLimit, WorldStaysValidAfterASinkThrows) {
    WorldSettings small_chunks;
    small_chunks.pair_chunk_size = 16;
    World2d world(small_chunks);
    std::vector<Box2d> boxes;
    for (int i = 0; i < 200; ++i) {
        const double x = (i % 20) * 0.9;
        const double y = (i / 20) * 0.9;
        boxes.push_back(Box2d{{x, y}, {x + 1, y + 1}});
    }
    world.assign(boxes);
    int calls = 0;
    auto throwing_sink = [&](std::span<const Pair>) {
        if (++calls == 2) throw std::runtime_error("consumer gave up");
    };
    EXPECT_THROW(world.detect(throwing_sink), std::runtime_error);
    std::vector<Pair> pairs;
    world.detect(pairs);
    sort_pairs(pairs);
    const auto expected = test::brute_force_pairs<double, 2>(std::span<const Box2d>(boxes));
    EXPECT_EQ(pairs, expected);
    EXPECT_EQ(world.size(), boxes.size());
}

// Many columns of cells, so that several threads work in several rounds while the calling
// thread hands the pairs on.
std::vector<Box3d> scattered_boxes(std::size_t n) {
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> place(0.0, 60.0);
    std::vector<Box3d> boxes;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = place(random), y = place(random), z = place(random);
        boxes.push_back(Box3d{{x, y, z}, {x + 1.5, y + 1.5, z + 1.5}});
    }
    return boxes;
}

TEST(PairLimit, SinkRunsOnTheCallingThreadAndMayThrowWhateverTheThreadCount) {
    const std::vector<Box3d> boxes = scattered_boxes(40000);
    const auto expected = test::brute_force_pairs<double, 3>(std::span<const Box3d>(boxes));
    ASSERT_GT(expected.size(), 2000U);
    for (const std::size_t threads : {1U, 2U, 3U}) {
        WorldSettings settings;
        settings.threads = threads;
        settings.pair_chunk_size = 100;
        World3d world(settings);
        world.assign(boxes);
        const std::thread::id caller = std::this_thread::get_id();
        for (const int throw_at : {1, 5, 17}) {
            int calls = 0;
            auto throwing_sink = [&](std::span<const Pair>) {
                EXPECT_EQ(std::this_thread::get_id(), caller) << threads << " threads";
                if (++calls == throw_at) throw std::runtime_error("consumer gave up");
            };
            EXPECT_THROW(world.detect(throwing_sink), std::runtime_error) << threads << " threads";
        }
        std::vector<Pair> pairs;
        world.detect([&](std::span<const Pair> chunk) {
            EXPECT_EQ(std::this_thread::get_id(), caller) << threads << " threads";
            pairs.insert(pairs.end(), chunk.begin(), chunk.end());
        });
        sort_pairs(pairs);
        EXPECT_EQ(pairs, expected) << threads << " threads";
    }
}

}  // namespace
}  // namespace smb
