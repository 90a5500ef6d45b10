// SPDX-License-Identifier: MIT
// How smb writes numbers in what it tells the user: a count takes the singular noun only when it
// is 1 ("1 frame", "2 frames"), and a number reads as the user wrote it or in its shortest form
// ("not 0.1", never std::to_string's "0.100000").

#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

/// Whether `text` holds a number printed with exactly six decimals, as std::to_string and "%f"
/// print a double.
/// (A plain scan rather than <regex>: GCC 12's std::regex trips -Wmaybe-uninitialized in the
/// sanitizer build, where warnings are errors.)
bool has_fixed_six_decimals(const std::string& text) {
    auto digit = [&](std::size_t i) {
        return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0;
    };
    for (std::size_t dot = 1; dot < text.size(); ++dot) {
        if (text[dot] != '.' || !digit(dot - 1)) continue;
        std::size_t decimals = 0;
        while (digit(dot + 1 + decimals)) ++decimals;
        if (decimals == 6) return true;
    }
    return false;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Whether `text` says "1 <plural>" as whole words ("1 steps", not "21 steps" or "1 stepsize").
bool has_one_with_plural(const std::string& text, const std::string& plural) {
    auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; };
    const std::string phrase = "1 " + plural;
    for (std::size_t at = text.find(phrase); at != std::string::npos; at = text.find(phrase, at + 1)) {
        const std::size_t end = at + phrase.size();
        if ((at == 0 || !word_char(text[at - 1])) && (end == text.size() || !word_char(text[end]))) return true;
    }
    return false;
}

TEST(CliMessages, GenerateCountsFramesInTheSingularForOne) {
    TempFolder folder;
    const auto one = run_smb(folder, {"generate", "-n", "10", "-s", "1", "-o", "scene.csv"});
    ASSERT_EQ(one.status, 0) << one.err;
    EXPECT_TRUE(contains(one.err, "smb generate: 1 frame of 3D boxes")) << one.err;
    const auto two = run_smb(folder, {"generate", "-n", "10", "-s", "2", "-o", "scene.csv"});
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_TRUE(contains(two.err, "smb generate: 2 frames of 3D boxes")) << two.err;
}

TEST(CliMessages, RunSummaryCountsStepsInTheSingularForOne) {
    TempFolder folder;
    const auto one = run_smb(folder, {"run", "-n", "300", "-s", "1"});
    ASSERT_EQ(one.status, 0) << one.err;
    EXPECT_TRUE(contains(one.out, ", 1 step, seed")) << one.out;
    EXPECT_TRUE(contains(one.out, "OK, 1 step equals the grid reference")) << one.out;

    const auto two = run_smb(folder, {"run", "-n", "300", "-s", "2"});
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_TRUE(contains(two.out, ", 2 steps, seed")) << two.out;
    EXPECT_TRUE(contains(two.out, "detect (1 step)")) << two.out;

    const auto three = run_smb(folder, {"run", "-n", "300", "-s", "3", "--check-every", "1"});
    ASSERT_EQ(three.status, 0) << three.err;
    EXPECT_TRUE(contains(three.out, "detect (2 steps)")) << three.out;
    EXPECT_TRUE(contains(three.out, "OK, 3 steps equal the grid reference")) << three.out;

    const auto skin = run_smb(folder, {"run", "-n", "300", "-s", "2", "--pipeline", "detector", "--skin", "0.1"});
    ASSERT_EQ(skin.status, 0) << skin.err;
    EXPECT_TRUE(contains(skin.out, "rebuilt in 0 of 1 step;") || contains(skin.out, "rebuilt in 1 of 1 step;"))
        << skin.out;
    for (const std::string& text : {one.out, two.out, three.out, skin.out}) {
        for (const char* noun : {"steps", "frames", "pairs", "candidates", "boxes"})
            EXPECT_FALSE(has_one_with_plural(text, noun)) << text;
    }
}

TEST(CliMessages, RejectedValuesReadAsTheUserWroteThem) {
    TempFolder folder;
    struct Case {
        std::vector<std::string> arguments;
        std::string expected;
    };
    const std::vector<Case> cases{
        {{"run", "-H", "0.1"}, "--size-ratio: must be in [1, 1000000000000], not 0.1"},
        {{"run", "-L", "1.5"}, "--update-factor: must be in [0, 1), not 1.5"},
        {{"run", "-E", "0"}, "--density: must be greater than 0, not 0"},
        {{"run", "--skin", "-0.25"}, "--skin: must be at least 0, not -0.25"},
        {{"run", "--segment-rule", "paper"}, "--segment-rule: needs --pipeline paper"},
        {{"run", "-s", "0"}, "--steps: must be at least 1, not 0"},
        {{"run", "-n", "-5"}, "--boxes: must be at least 0, not -5"},
        {{"run", "--threads", "2000"}, "--threads: must be in [0, 1024], not 2000"},
        {{"generate", "--side", "-3"}, "--side: must be greater than 0, not -3"},
        {{"pairs", "--pairs-in-memory", "1"}, "--pairs-in-memory: must be at least 2, not 1"},
        {{"run", "-L", "much"}, "--update-factor: must be a number in [0, 1), not 'much'"},
    };
    for (const Case& bad : cases) {
        const auto result = run_smb(folder, bad.arguments);
        EXPECT_NE(result.status, 0);
        EXPECT_TRUE(contains(result.err, bad.expected)) << bad.expected << '\n' << result.err;
        EXPECT_FALSE(has_fixed_six_decimals(result.err)) << result.err;
    }
}

TEST(CliMessages, TooSmallCubeReadsInShortestForm) {
    TempFolder folder;
    const auto side = run_smb(folder, {"generate", "-n", "3", "-s", "1", "--side", "0.5"});
    EXPECT_EQ(side.status, 1);
    EXPECT_TRUE(contains(side.err, "the cube side x = 0.5 is smaller than the largest box side b = 1")) << side.err;
    const auto density = run_smb(folder, {"run", "-n", "1", "-E", "0.9"});
    EXPECT_EQ(density.status, 1);
    EXPECT_TRUE(contains(density.err, "the cube side x = 0.7250209180559003 is smaller")) << density.err;
    EXPECT_FALSE(has_fixed_six_decimals(side.err + density.err));

    const auto empty = run_smb(folder, {"generate", "-n", "0", "-s", "1"});
    EXPECT_EQ(empty.status, 1);
    EXPECT_TRUE(contains(empty.err, "an empty scene (N = 0) has no cube side at a density: give --side")) << empty.err;
    const auto empty_with_side = run_smb(folder, {"generate", "-n", "0", "-s", "2", "--side", "5"});
    EXPECT_EQ(empty_with_side.status, 0) << empty_with_side.err;
    EXPECT_EQ(empty_with_side.out, "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n");
}

TEST(CliMessages, OutputOfNormalRunsHasNoSixDecimalNumbers) {
    TempFolder folder;
    const auto generate = run_smb(folder, {"generate", "-n", "20", "-s", "2", "-H", "1.5", "-o", "scene.csv"});
    ASSERT_EQ(generate.status, 0) << generate.err;
    EXPECT_FALSE(has_fixed_six_decimals(generate.err)) << generate.err;
    const auto run = run_smb(folder, {"run", "-n", "300", "-s", "3", "-H", "1.5", "-L", "0.01"});
    ASSERT_EQ(run.status, 0) << run.err;
    // Times print with three decimals; no quantity prints in std::to_string's form.
    EXPECT_FALSE(has_fixed_six_decimals(run.out)) << run.out;
}

TEST(CliMessages, AnUnknownHeaderIsShownEscapedAndCut) {
    TempFolder folder;
    // Terminal escapes, a NUL and a long tail: none of it may reach the terminal as it is.
    std::string header = "\x1b[2J\x1b]0;title\aframe";  // \a: the terminal bell, 0x07
    header += '\0';
    // Appended piece by piece: GCC 12 at -O3 mistakes "literal" + std::string for an overflow.
    header += ",id";
    header.append(5000, 'x');
    header += "\n0,1,0,0,1,1\n";
    write_file(folder / "scene.csv", header);
    const auto scene = run_smb(folder, {"pairs", "-i", "scene.csv"});
    const auto pairs = run_smb(folder, {"join", "--left", "scene.csv", "--right", "scene.csv"});
    for (const auto* result : {&scene, &pairs}) {
        EXPECT_EQ(result->status, 1) << result->err;
        EXPECT_TRUE(contains(result->err, "unknown header '\\x1b[2J\\x1b]0;title\\x07frame\\x00,id")) << result->err;
        for (const char c : result->err) {
            const auto byte = static_cast<unsigned char>(c);
            EXPECT_TRUE(c == '\n' || (byte >= 0x20 && byte < 0x7f)) << "byte " << int(byte) << " in " << result->err;
        }
        EXPECT_LT(result->err.size(), 400u) << result->err;
    }
}

}  // namespace
}  // namespace smb::cli_test
