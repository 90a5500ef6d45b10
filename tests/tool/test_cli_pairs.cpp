// SPDX-License-Identifier: MIT
// `smb pairs` end to end: the built binary on small scene files, compared with expected pair
// files and with brute force on generated scenes; error exits, messages and leftover files.

#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "pair_csv.hpp"
#include "reference/brute_force.hpp"
#include "scene_csv.hpp"
#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

constexpr const char* header_2d = "frame,id,xmin,ymin,xmax,ymax\n";

/// The pair CSV that brute force gives for every frame of a scene CSV.
template <int Dim>
std::vector<io::FramePair> brute_force_pairs_of(const fs::path& scene_path) {
    std::ifstream in(scene_path, std::ios::binary);
    io::SceneReader reader(in, scene_path.string());
    std::vector<io::FramePair> rows;
    io::SceneFrame<Dim> frame;
    while (reader.read_frame(frame)) {
        const auto pairs = test::brute_force_pairs<double, Dim>(frame.ids, frame.boxes);
        for (const Pair& pair : pairs) rows.push_back({frame.number, pair.a, pair.b});
    }
    return rows;
}

std::vector<io::FramePair> parse_pairs(const std::string& text) {
    std::istringstream in(text);
    return io::read_pair_csv(in, "output");
}

TEST(CliPairs, FixtureFileToFile) {
    TempFolder folder;
    const auto result =
        run_smb(folder, {"pairs", "--input", data_file("basic_3d.csv").string(), "--output", "pairs.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(read_file(folder / "pairs.csv"), read_file(data_file("basic_3d.pairs.csv")));
    EXPECT_EQ(folder.entry_count(), 1u);  // no temporary left behind
}

TEST(CliPairs, CrlfWithoutFinalNewline) {
    TempFolder folder;
    const auto result = run_smb(folder, {"pairs", "-i", data_file("crlf_2d.csv").string(), "-o", "-"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, read_file(data_file("crlf_2d.pairs.csv")));
}

TEST(CliPairs, StandardInputAndOutput) {
    TempFolder folder;
    const auto dashes = run_smb(folder, {"pairs", "--input", "-", "--output", "-"}, data_file("basic_3d.csv"));
    ASSERT_EQ(dashes.status, 0) << dashes.err;
    EXPECT_EQ(dashes.out, read_file(data_file("basic_3d.pairs.csv")));
    EXPECT_TRUE(dashes.err.empty());

    const auto defaults = run_smb(folder, {"pairs"}, data_file("basic_3d.csv"));
    ASSERT_EQ(defaults.status, 0) << defaults.err;
    EXPECT_EQ(defaults.out, dashes.out);
}

TEST(CliPairs, HeaderOnlySceneGivesHeaderOnlyPairs) {
    TempFolder folder;
    const auto result = run_smb(folder, {"pairs"}, data_file("header_only_3d.csv"));
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "frame,a,b\n");
}

template <int Dim>
void expect_generated_scene_matches_brute_force(const std::string& dimension) {
    TempFolder folder;
    // A large update factor makes boxes appear and disappear every step.
    const auto generated = run_smb(folder, {"generate", "--dim", dimension, "-n", "400", "-s", "6", "-L", "0.05",
                                            "--seed", "3", "-o", "scene.csv"});
    ASSERT_EQ(generated.status, 0) << generated.err;
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "pairs.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto expected = brute_force_pairs_of<Dim>(folder / "scene.csv");
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(parse_pairs(read_file(folder / "pairs.csv")), expected);
}

TEST(CliPairs, GeneratedScene3dMatchesBruteForce) { expect_generated_scene_matches_brute_force<3>("3"); }
TEST(CliPairs, GeneratedScene2dMatchesBruteForce) { expect_generated_scene_matches_brute_force<2>("2"); }

struct BadScene {
    const char* name;
    std::string text;
    int line;
    const char* words;
};

class CliPairsErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(CliPairsErrors, ExitNonZeroNamingFileAndLineAndLeaveNoOutput) {
    const BadScene& bad = GetParam();
    TempFolder folder;
    write_file(folder / "scene.csv", bad.text);
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "pairs.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("scene.csv:" + std::to_string(bad.line) + ": "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(bad.words), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(folder / "pairs.csv"));
    EXPECT_EQ(folder.entry_count(), 1u);  // only scene.csv: no temporary either
}

// Valid frames come first wherever possible, so that output has begun when the error hits.
const std::string good_frames = std::string(header_2d) + "0,1,0,0,1,1\n0,2,0.5,0.5,2,2\n";

INSTANTIATE_TEST_SUITE_P(
    EveryMalformedCase, CliPairsErrors,
    ::testing::Values(BadScene{"EmptyFile", "", 1, "empty file"},
                      BadScene{"UnknownHeader", "frame,id,x,y,z\n", 1, "unknown header"},
                      BadScene{"WrongColumnCount", good_frames + "1,1,0,0,1\n", 4, "expected 6 fields"},
                      BadScene{"TextInNumber", good_frames + "1,1,0,zero,1,1\n", 4, "not a number"},
                      BadScene{"NaN", good_frames + "1,1,0,NaN,1,1\n", 4, "not finite"},
                      BadScene{"Infinity", good_frames + "1,1,0,0,inf,1\n", 4, "not finite"},
                      BadScene{"MinAboveMax", good_frames + "1,1,2,0,1,1\n", 4, "xmin 2 is greater than xmax 1"},
                      BadScene{"DuplicateId", good_frames + "1,1,0,0,1,1\n1,1,0,0,1,1\n", 5, "appears twice"},
                      BadScene{"FramesOutOfOrder", good_frames + "3,1,0,0,1,1\n2,1,0,0,1,1\n", 5,
                               "frames must not decrease"},
                      BadScene{"NegativeFrame", good_frames + "-1,1,0,0,1,1\n", 4, "negative"},
                      BadScene{"NegativeId", good_frames + "1,-1,0,0,1,1\n", 4, "negative"},
                      BadScene{"IdOverflow", good_frames + "1,99999999999999999999,0,0,1,1\n", 4, "64 bits"}),
    [](const auto& instance) { return std::string(instance.param.name); });

TEST(CliPairs, FailedRunKeepsThePreviousOutputFile) {
    TempFolder folder;
    write_file(folder / "scene.csv", good_frames + "1,1,0,0,1\n");
    write_file(folder / "pairs.csv", "previous\n");
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "pairs.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_EQ(read_file(folder / "pairs.csv"), "previous\n");
    EXPECT_EQ(folder.entry_count(), 2u);
}

TEST(CliPairs, ErrorOnStandardInputNamesIt) {
    TempFolder folder;
    write_file(folder / "scene.csv", good_frames + "0,1,0,0,1,1\n");
    const auto result = run_smb(folder, {"pairs"}, folder / "scene.csv");
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("<stdin>:4: id 1 appears twice"), std::string::npos) << result.err;
}

TEST(CliPairs, MissingInputFile) {
    TempFolder folder;
    const auto result = run_smb(folder, {"pairs", "-i", "absent.csv", "-o", "pairs.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("absent.csv"), std::string::npos) << result.err;
    EXPECT_EQ(folder.entry_count(), 0u);
}

/// Reads what arrives on `descriptor` within `limit`, until `wanted` has been seen.
std::string read_until(int descriptor, const std::string& wanted, std::chrono::seconds limit) {
    std::string seen;
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (seen.find(wanted) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
        pollfd ready{descriptor, POLLIN, 0};
        if (::poll(&ready, 1, 100) <= 0) continue;
        char buffer[256];
        const ssize_t count = ::read(descriptor, buffer, sizeof buffer);
        if (count <= 0) break;
        seen.append(buffer, static_cast<std::size_t>(count));
    }
    return seen;
}

// `smb pairs` without --input on a terminal would otherwise wait for typed input in silence.
TEST(CliPairs, ReadingATerminalSaysSo) {
    int terminal = -1;
    const pid_t child = ::forkpty(&terminal, nullptr, nullptr, nullptr);
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::execl(SMB_CLI_PATH, SMB_CLI_PATH, "pairs", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    const std::string said = read_until(terminal, "Ctrl-D", std::chrono::seconds(10));
    EXPECT_NE(said.find("smb pairs: reading a scene CSV from standard input"), std::string::npos) << said;
    // End of input at the start of a line: the empty input is refused as an empty file.
    ASSERT_EQ(::write(terminal, "\x04", 1), 1);
    const std::string rest = read_until(terminal, "empty file", std::chrono::seconds(10));
    int status = 0;
    for (int waited = 0; ::waitpid(child, &status, WNOHANG) == 0; ++waited) {
        if (waited == 1000) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::close(terminal);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << said << rest;
    EXPECT_NE(rest.find("<stdin>:1: empty file"), std::string::npos) << rest;
}

TEST(CliPairs, UnknownOptionIsRejected) {
    TempFolder folder;
    const auto result = run_smb(folder, {"pairs", "--frobnicate"});
    EXPECT_NE(result.status, 0);
    EXPECT_FALSE(result.err.empty());
}

}  // namespace
}  // namespace smb::cli_test
