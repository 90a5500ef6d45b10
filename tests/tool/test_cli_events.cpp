// SPDX-License-Identifier: MIT
// `smb pairs --events` end to end: the built binary on hand-written scenes with their exact
// event CSV, and on random scenes (ids vanishing and coming back, skipped frame numbers)
// against events derived from brute-force pairs by the rules of the event CSV; a malformed
// scene leaves no output file.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "reference/brute_force.hpp"
#include "scene_csv.hpp"
#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

constexpr const char* header_2d = "frame,id,xmin,ymin,xmax,ymax\n";

/// The event CSV of a scene by the rules of its format, from brute-force pairs of every frame.
std::string expected_events(const fs::path& scene_path) {
    std::ifstream in(scene_path, std::ios::binary);
    io::SceneReader reader(in, scene_path.string());
    io::SceneFrame<2> frame;
    std::set<Pair> before;
    bool first = true;
    std::uint64_t previous_number = 0;
    std::vector<std::tuple<std::uint64_t, Pair, std::string>> rows;
    while (reader.read_frame(frame)) {
        if (!first && frame.number > previous_number + 1) {
            for (const Pair& pair : before) rows.emplace_back(previous_number + 1, pair, "end");
            before.clear();
        }
        const auto pairs = test::brute_force_pairs<double, 2>(frame.ids, frame.boxes);
        const std::set<Pair> now(pairs.begin(), pairs.end());
        for (const Pair& pair : now) {
            if (!before.contains(pair)) rows.emplace_back(frame.number, pair, "begin");
        }
        for (const Pair& pair : before) {
            if (!now.contains(pair)) rows.emplace_back(frame.number, pair, "end");
        }
        before = now;
        previous_number = frame.number;
        first = false;
    }
    std::sort(rows.begin(), rows.end());
    std::string text = "frame,a,b,event\n";
    for (const auto& [number, pair, event] : rows) {
        text += std::to_string(number) + "," + std::to_string(pair.a) + "," + std::to_string(pair.b) + "," + event;
        text += "\n";
    }
    return text;
}

TEST(CliEvents, HandWrittenScene) {
    TempFolder folder;
    // Frame 0: 1-2 and 2-3 touch. Frame 1: 3 moves off, 4 arrives on 1. Frame 2: 1 vanishes.
    // Frame 3 is skipped: every pair ends there. Frame 4: 2 and 4 overlap again.
    write_file(folder / "scene.csv", std::string(header_2d) +
                                         "0,1,0,0,1,1\n0,2,1,0,2,1\n0,3,2,0,3,1\n"
                                         "1,1,0,0,1,1\n1,2,1,0,2,1\n1,3,5,0,6,1\n1,4,0.5,0.5,1.5,1.5\n"
                                         "2,2,1,0,2,1\n2,4,0.5,0.5,1.5,1.5\n"
                                         "4,2,1,0,2,1\n4,4,0.5,0.5,1.5,1.5\n");
    const auto result = run_smb(folder, {"pairs", "--events", "-i", "scene.csv", "-o", "events.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_file(folder / "events.csv"),
              "frame,a,b,event\n"
              "0,1,2,begin\n0,2,3,begin\n"
              "1,1,4,begin\n1,2,3,end\n1,2,4,begin\n"
              "2,1,2,end\n2,1,4,end\n"
              "3,2,4,end\n"
              "4,2,4,begin\n");
    EXPECT_EQ(folder.entry_count(), 2u);  // no temporary left behind
}

TEST(CliEvents, FirstFrameWithoutPairsAndLateFirstNumber) {
    TempFolder folder;
    // The first frame, numbered 5, has no contacts: no rows. Nothing ends after the last frame.
    write_file(folder / "scene.csv", std::string(header_2d) + "5,1,0,0,1,1\n5,2,3,0,4,1\n6,1,0,0,1,1\n6,2,1,0,2,1\n");
    const auto result = run_smb(folder, {"pairs", "--events", "-i", "scene.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "frame,a,b,event\n6,1,2,begin\n");
    write_file(folder / "one.csv", std::string(header_2d) + "0,1,0,0,1,1\n");
    const auto single = run_smb(folder, {"pairs", "--events", "-i", "one.csv"});
    ASSERT_EQ(single.status, 0) << single.err;
    EXPECT_EQ(single.out, "frame,a,b,event\n");
}

/// Body `k`'s id in the scenes with ids across the whole 64-bit range: the edges, where a
/// narrowing or packing of ids would show, then k times an odd constant.
BoxId wide_id(std::size_t k) {
    constexpr BoxId edges[] = {std::numeric_limits<BoxId>::max(),
                               BoxId{1} << 32,
                               (BoxId{1} << 32) - 1,
                               BoxId{1} << 63,
                               (BoxId{1} << 63) - 1,
                               (BoxId{1} << 32) + 1,
                               0,
                               7};
    return k < std::size(edges) ? edges[k] : static_cast<BoxId>(k) * 0x9E3779B97F4A7C15u;
}

TEST(CliEvents, RandomScenesMatchBruteForce) {
    std::mt19937_64 random(31);
    std::uniform_real_distribution<double> unit(0, 1);
    for (int trial = 0; trial < 4; ++trial) {
        const bool wide = trial >= 2;  // ids across the whole 64-bit range
        TempFolder folder;
        std::ostringstream scene;
        scene << header_2d;
        std::vector<std::array<double, 2>> centre(80);
        for (auto& c : centre) c = {12 * unit(random), 12 * unit(random)};
        std::uint64_t number = 0;
        for (int f = 0; f < 14; ++f) {
            number += unit(random) < 0.2 ? 2 + static_cast<std::uint64_t>(3 * unit(random)) : 1;
            for (std::size_t id = 0; id < centre.size(); ++id) {
                if (unit(random) < 0.15) continue;  // absent from this frame: removed, maybe back later
                auto& c = centre[id];
                if (unit(random) < 0.05) c = {12 * unit(random), 12 * unit(random)};  // teleported
                c[0] += 0.3 * (unit(random) - 0.5);
                c[1] += 0.3 * (unit(random) - 0.5);
                // Sides on a grid of quarters, so that some boxes touch exactly.
                const double half = 0.25 * static_cast<double>(1 + static_cast<int>(4 * unit(random)));
                scene << number << ',' << (wide ? wide_id(id) : id) << ',' << c[0] - half << ',' << c[1] - half << ','
                      << c[0] + half << ',' << c[1] + half << '\n';
            }
        }
        write_file(folder / "scene.csv", scene.str());
        const auto result = run_smb(folder, {"pairs", "--events", "-i", "scene.csv", "-o", "events.csv"});
        ASSERT_EQ(result.status, 0) << result.err;
        const std::string expected = expected_events(folder / "scene.csv");
        EXPECT_GT(std::count(expected.begin(), expected.end(), '\n'), 100) << "too few events to test";
        EXPECT_EQ(read_file(folder / "events.csv"), expected) << trial;
    }
}

TEST(CliEvents, MalformedSceneLeavesNoOutput) {
    TempFolder folder;
    write_file(folder / "scene.csv", std::string(header_2d) + "0,1,0,0,1,1\n0,2,0.5,0.5,2,2\n1,1,2,0,1,1\n");
    write_file(folder / "events.csv", "previous\n");
    const auto result = run_smb(folder, {"pairs", "--events", "-i", "scene.csv", "-o", "events.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("scene.csv:4: "), std::string::npos) << result.err;
    EXPECT_EQ(read_file(folder / "events.csv"), "previous\n");
    EXPECT_EQ(folder.entry_count(), 2u);
}

}  // namespace
}  // namespace smb::cli_test
