// How smb writes numbers in what it tells the user: a count takes the singular noun only when it
// is 1 ("1 frame", "2 frames"), and no number prints in std::to_string's form ("0.100000").

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

/// Whether `text` holds a number printed with exactly six decimals, as std::to_string and "%f"
/// print a double.
bool has_fixed_six_decimals(const std::string& text) {
    return std::regex_search(text, std::regex(R"(\d\.\d{6}(?!\d))"));
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
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
    EXPECT_TRUE(std::regex_search(skin.out, std::regex(R"(rebuilt in [01] of 1 step;)"))) << skin.out;
    for (const std::string& text : {one.out, two.out, three.out, skin.out}) {
        EXPECT_FALSE(std::regex_search(text, std::regex(R"(\b1 (steps|frames|pairs|candidates|boxes)\b)")))
            << text;
    }
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

}  // namespace
}  // namespace smb::cli_test
