// Pair explosions: detect(vector) refuses to hold more than max_pairs_held pairs, detect(sink)
// streams any number, and a sink that throws leaves the world valid.

#include <gtest/gtest.h>

#include <stdexcept>
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

}  // namespace
}  // namespace smb
