// SPDX-License-Identifier: MIT
// `smb join` end to end: the built binary on two scene files, compared with an expected join
// CSV and with brute force over random scenes whose frames come and go on each side; errors in
// either file, a dimension mismatch, and the output file left as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "scene_csv.hpp"
#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

constexpr const char* header_2d = "frame,id,xmin,ymin,xmax,ymax\n";
constexpr const char* header_3d = "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n";

using JoinRow = std::tuple<std::uint64_t, BoxId, BoxId>;  // frame, left, right

/// The rows of a join CSV, checking its header.
std::vector<JoinRow> parse_join(const std::string& text) {
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "frame,left,right");
    std::vector<JoinRow> rows;
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::uint64_t frame = 0;
        BoxId left = 0;
        BoxId right = 0;
        char comma = 0;
        fields >> frame >> comma >> left >> comma >> right;
        rows.emplace_back(frame, left, right);
    }
    return rows;
}

TEST(CliJoin, FramesOnOneSideSkippedFramesAndSharedIds) {
    TempFolder folder;
    // Left: frames 0, 1, 3, 6. Right: frames 0, 2, 3, 4. Frame 5 is in neither. Both use id 1.
    write_file(folder / "left.csv", std::string(header_2d) +
                                        "0,1,0,0,1,1\n"
                                        "0,2,5,5,6,6\n"
                                        "1,1,0,0,1,1\n"
                                        "3,9,0,0,2,2\n"
                                        "3,1,4,4,5,5\n"
                                        "6,1,0,0,1,1\n");
    write_file(folder / "right.csv", std::string(header_2d) +
                                         "0,1,1,1,2,2\n"  // touches left 1 at a corner
                                         "0,3,0.5,0.5,0.7,0.7\n"
                                         "2,1,0,0,1,1\n"      // no left box in frame 2
                                         "3,1,2,2,3,3\n"      // touches left 9
                                         "3,2,4.5,4.5,9,9\n"  // overlaps left 1 only
                                         "3,7,0,0,10,10\n"    // covers both
                                         "4,7,0,0,10,10\n");  // no left frame 4
    const auto result = run_smb(folder, {"join", "--left", "left.csv", "--right", "right.csv", "--output", "out.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_file(folder / "out.csv"),
              "frame,left,right\n"
              "0,1,1\n"
              "0,1,3\n"
              "3,1,2\n"
              "3,1,7\n"
              "3,9,1\n"
              "3,9,7\n");
    EXPECT_EQ(folder.entry_count(), 3u);  // no temporary left behind
}

TEST(CliJoin, IdsAcrossTheWholeRange) {
    TempFolder folder;
    // Every left box overlaps every right box; the sides share 2^64 - 1.
    write_file(folder / "left.csv", std::string(header_2d) +
                                        "0,18446744073709551615,0,0,1,1\n"
                                        "0,4294967296,0,0,1,1\n"
                                        "0,0,0,0,1,1\n");
    write_file(folder / "right.csv", std::string(header_2d) +
                                         "0,4294967295,1,1,2,2\n"
                                         "0,9223372036854775808,0.5,0.5,2,2\n"
                                         "0,18446744073709551615,0,0,1,1\n");
    const auto result = run_smb(folder, {"join", "--left", "left.csv", "--right", "right.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out,
              "frame,left,right\n"
              "0,0,4294967295\n"
              "0,0,9223372036854775808\n"
              "0,0,18446744073709551615\n"
              "0,4294967296,4294967295\n"
              "0,4294967296,9223372036854775808\n"
              "0,4294967296,18446744073709551615\n"
              "0,18446744073709551615,4294967295\n"
              "0,18446744073709551615,9223372036854775808\n"
              "0,18446744073709551615,18446744073709551615\n");
}

TEST(CliJoin, EmptyScenesGiveTheHeaderOnly) {
    TempFolder folder;
    write_file(folder / "left.csv", header_3d);
    write_file(folder / "right.csv", std::string(header_3d) + "0,1,0,0,0,1,1,1\n");
    const auto result = run_smb(folder, {"join", "-l", "left.csv", "-r", "right.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "frame,left,right\n");
}

TEST(CliJoin, OneSideFromStandardInput) {
    TempFolder folder;
    write_file(folder / "left.csv", std::string(header_2d) + "0,4,0,0,1,1\n");
    write_file(folder / "right.csv", std::string(header_2d) + "0,8,1,0,2,1\n");
    const auto result = run_smb(folder, {"join", "-l", "-", "-r", "right.csv"}, folder / "left.csv");
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "frame,left,right\n0,4,8\n");
    EXPECT_EQ(run_smb(folder, {"join", "-l", "-", "-r", "-"}).status, 64);
}

/// A random scene of `frames` frames, each present with probability `presence`: boxes come,
/// move and go, ids drawn from a small pool so that both scenes use the same ids.
template <int Dim>
std::vector<std::vector<std::pair<BoxId, Box<double, Dim>>>> random_scene(std::mt19937_64& random, int frames,
                                                                          double presence) {
    std::uniform_real_distribution<double> coordinate(0, 12);
    std::uniform_real_distribution<double> side(0.2, 2.0);
    std::bernoulli_distribution keep(0.8);
    std::bernoulli_distribution present(presence);
    std::vector<std::vector<std::pair<BoxId, Box<double, Dim>>>> scene(static_cast<std::size_t>(frames));
    for (auto& frame : scene) {
        if (!present(random)) continue;
        for (BoxId id = 0; id < 120; ++id) {
            if (!keep(random)) continue;
            Box<double, Dim> box;
            for (int k = 0; k < Dim; ++k) {
                box.min[k] = std::round(coordinate(random) * 4) / 4;  // quarters: many touching boxes
                box.max[k] = box.min[k] + std::round(side(random) * 4) / 4;
            }
            frame.emplace_back(id * 3, box);
        }
    }
    return scene;
}

template <int Dim>
std::string scene_text(const std::vector<std::vector<std::pair<BoxId, Box<double, Dim>>>>& scene) {
    std::ostringstream out;
    {
        io::SceneWriter writer(out, Dim);
        for (std::size_t f = 0; f < scene.size(); ++f) {
            std::vector<BoxId> ids;
            std::vector<Box<double, Dim>> boxes;
            for (const auto& [id, box] : scene[f]) {
                ids.push_back(id);
                boxes.push_back(box);
            }
            writer.write_frame<Dim>(f, ids, boxes);
        }
        writer.flush();
    }
    return out.str();
}

template <int Dim>
void expect_random_scenes_match_brute_force(std::uint64_t seed) {
    std::mt19937_64 random(seed);
    const int frames = 10;
    const auto left = random_scene<Dim>(random, frames, 0.7);
    const auto right = random_scene<Dim>(random, frames, 0.7);
    std::vector<JoinRow> expected;
    for (int f = 0; f < frames; ++f) {
        for (const auto& [left_id, left_box] : left[static_cast<std::size_t>(f)]) {
            for (const auto& [right_id, right_box] : right[static_cast<std::size_t>(f)]) {
                if (overlaps(left_box, right_box)) expected.emplace_back(f, left_id, right_id);
            }
        }
    }
    std::sort(expected.begin(), expected.end());
    TempFolder folder;
    write_file(folder / "left.csv", scene_text<Dim>(left));
    write_file(folder / "right.csv", scene_text<Dim>(right));
    const auto result = run_smb(folder, {"join", "-l", "left.csv", "-r", "right.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(parse_join(result.out), expected);
    EXPECT_FALSE(expected.empty());
}

TEST(CliJoin, RandomScenes2dMatchBruteForce) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) expect_random_scenes_match_brute_force<2>(seed);
}

TEST(CliJoin, RandomScenes3dMatchBruteForce) {
    for (std::uint64_t seed = 11; seed <= 13; ++seed) expect_random_scenes_match_brute_force<3>(seed);
}

struct MalformedCase {
    const char* name;
    const char* left;
    const char* right;
    const char* message;  ///< what stderr must contain
};

class CliJoinErrors : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(CliJoinErrors, ExitOneNamingFileAndLineAndKeepThePreviousOutput) {
    const MalformedCase& bad = GetParam();
    TempFolder folder;
    write_file(folder / "left.csv", bad.left);
    write_file(folder / "right.csv", bad.right);
    write_file(folder / "out.csv", "previous\n");
    const auto result = run_smb(folder, {"join", "-l", "left.csv", "-r", "right.csv", "-o", "out.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find(bad.message), std::string::npos) << result.err;
    EXPECT_EQ(read_file(folder / "out.csv"), "previous\n");
    EXPECT_EQ(folder.entry_count(), 3u);
}

constexpr const char* good_2d =
    "frame,id,xmin,ymin,xmax,ymax\n"
    "0,1,0,0,1,1\n"
    "1,1,0,0,1,1\n"
    "2,1,0,0,1,1\n";

INSTANTIATE_TEST_SUITE_P(
    EveryFile, CliJoinErrors,
    ::testing::Values(
        MalformedCase{"LeftField", "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n\n1,1,0,zero,1,1\n", good_2d,
                      "left.csv:4: ymin 'zero' is not a number"},
        MalformedCase{"RightLateFrame", good_2d, "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n2,1,0,0,1\n",
                      "right.csv:3: expected 6 fields, found 5"},
        MalformedCase{"RightMinAboveMax", good_2d, "frame,id,xmin,ymin,xmax,ymax\n1,5,3,0,2,1\n", "right.csv:2:"},
        MalformedCase{"LeftFramesOutOfOrder", "frame,id,xmin,ymin,xmax,ymax\n2,1,0,0,1,1\n1,1,0,0,1,1\n", good_2d,
                      "left.csv:3:"},
        MalformedCase{"DimensionMismatch", good_2d, "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n0,1,0,0,0,1,1,1\n",
                      "right.csv:1: a 3D scene, but the left scene left.csv is 2D: both scenes must have the same "
                      "dimension"},
        MalformedCase{"RightHeader", good_2d, "frame,a,b\n", "right.csv:1: unknown header"}),
    [](const ::testing::TestParamInfo<MalformedCase>& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace smb::cli_test
