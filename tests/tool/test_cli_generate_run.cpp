// SPDX-License-Identifier: MIT
// `smb generate` and `smb run` end to end: the written scene is exactly the workload library's
// environment, and `smb run` reports and checks what it measured.

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene_csv.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

TEST(CliGenerate, WritesExactlyTheEnvironment) {
    TempFolder folder;
    const auto result = run_smb(folder, {"generate", "--dim", "3", "-n", "300", "-s", "4", "-E", "0.3", "-H", "4", "-L",
                                         "0.02", "--seed", "9", "-o", "scene.csv"});
    ASSERT_EQ(result.status, 0) << result.err;

    workload::EnvironmentParams params;
    params.box_count = 300;
    params.packing_density = 0.3;
    params.size_ratio = 4;
    params.update_factor = 0.02;
    params.seed = 9;
    workload::DynamicEnvironment<3> environment(params);

    std::ifstream in(folder / "scene.csv", std::ios::binary);
    io::SceneReader reader(in, "scene.csv");
    ASSERT_EQ(reader.dimension(), 3);
    io::SceneFrame<3> frame;
    std::uint64_t frames = 0;
    while (reader.read_frame(frame)) {
        if (frames > 0) environment.step();
        EXPECT_EQ(frame.number, frames);
        ASSERT_TRUE(std::ranges::equal(frame.ids, environment.ids()));
        // Bitwise equal: the text round-trips every double.
        ASSERT_TRUE(std::ranges::equal(frame.boxes, environment.boxes()));
        ++frames;
    }
    EXPECT_EQ(frames, 4u);
}

TEST(CliGenerate, SameSeedSameBytesOtherSeedOtherBytes) {
    TempFolder folder;
    const std::vector<std::string> base{"generate", "--dim", "2", "-n", "200", "-s", "3"};
    auto with_seed = [&](const std::string& seed) {
        auto arguments = base;
        arguments.insert(arguments.end(), {"--seed", seed});
        const auto result = run_smb(folder, arguments);
        EXPECT_EQ(result.status, 0) << result.err;
        return result.out;
    };
    const std::string first = with_seed("5");
    EXPECT_TRUE(first.starts_with("frame,id,xmin,ymin,xmax,ymax\n"));
    EXPECT_EQ(first, with_seed("5"));
    EXPECT_NE(first, with_seed("6"));
}

TEST(CliGenerate, SideAndDensityExcludeEachOther) {
    TempFolder folder;
    EXPECT_NE(run_smb(folder, {"generate", "--side", "20", "-E", "0.3"}).status, 0);
    const auto side = run_smb(folder, {"generate", "--side", "20", "-n", "10", "-s", "1"});
    EXPECT_EQ(side.status, 0) << side.err;
}

TEST(CliGenerate, ImpossibleParametersFailCleanly) {
    TempFolder folder;
    const auto result = run_smb(folder, {"generate", "-n", "1", "-E", "0.9", "-o", "scene.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("cube side"), std::string::npos) << result.err;
    EXPECT_EQ(folder.entry_count(), 0u);
}

/// The phases of smb::DetectProfile, each under its field's name without "_seconds".
const std::vector<std::string> kPhaseKeys{"check",    "containment", "cut_regroup", "list_sort",
                                          "quantile", "scan",        "update"};

std::vector<std::string> phase_keys(const nlohmann::json& phases) {
    std::vector<std::string> keys;
    for (const auto& [key, value] : phases.items()) keys.push_back(key);
    std::sort(keys.begin(), keys.end());
    return keys;
}

double phase_sum(const nlohmann::json& phases) {
    double sum = 0;
    for (const auto& [key, value] : phases.items()) sum += value.get<double>();
    return sum;
}

TEST(CliRun, JsonSummaryOfASmallRun) {
    TempFolder folder;
    const auto result = run_smb(folder, {"run", "-n", "2000", "-s", "10", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["dimension"], 3);
    EXPECT_EQ(summary["steps"], 10);
    EXPECT_EQ(summary["boxes"]["initial"], 2000);
    EXPECT_DOUBLE_EQ(summary["packing_density"].get<double>(), 0.4);
    EXPECT_GT(summary["build_seconds"].get<double>(), 0);
    // The build's phases are disjoint parts of it; the first detection always selects the
    // quantiles of its cuts, and the persistent cuts sort no lists.
    const auto& build_phases = summary["build_phase_seconds"];
    EXPECT_GT(build_phases["quantile"].get<double>(), 0);
    EXPECT_EQ(build_phases["list_sort"].get<double>(), 0);
    EXPECT_EQ(build_phases["containment"].get<double>(), 0);
    EXPECT_LE(phase_sum(build_phases), summary["build_seconds"].get<double>());
    EXPECT_EQ(phase_keys(build_phases), kPhaseKeys);
    EXPECT_EQ(phase_keys(summary["phase_seconds_median"]), kPhaseKeys);
    EXPECT_LE(summary["detect_seconds"]["min"].get<double>(), summary["detect_seconds"]["median"].get<double>());
    EXPECT_LE(summary["detect_seconds"]["min"].get<double>(), summary["detect_seconds"]["mean"].get<double>());
    EXPECT_LE(summary["detect_seconds"]["mean"].get<double>(), summary["detect_seconds"]["max"].get<double>());
    EXPECT_GE(summary["detect_cpu_seconds"]["median"].get<double>(), 0);
    EXPECT_GT(summary["pairs"]["last"].get<std::size_t>(), 0u);
    EXPECT_GT(summary["bytes_per_box"].get<double>(), 0);
    EXPECT_GT(summary["boxes"]["median"].get<double>(), 0);
    EXPECT_GT(summary["peak_rss_bytes"].get<std::size_t>(), summary["bytes_held"].get<std::size_t>());
    EXPECT_TRUE(summary["check"]["ok"].get<bool>());
    EXPECT_EQ(summary["check"]["steps_checked"], 1);
    EXPECT_EQ(summary["check"]["last_checked_step"], 10);
}

TEST(CliRun, PaperPipelineTimesItsListSortsNotQuantiles) {
    TempFolder folder;
    const auto result = run_smb(folder, {"run", "-n", "2000", "-s", "4", "--pipeline", "paper", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    const auto& build_phases = summary["build_phase_seconds"];
    EXPECT_GT(build_phases["list_sort"].get<double>(), 0);
    EXPECT_EQ(build_phases["quantile"].get<double>(), 0);
    EXPECT_EQ(build_phases["scan"].get<double>(), 0);
    EXPECT_LE(phase_sum(build_phases), summary["build_seconds"].get<double>());
    EXPECT_EQ(summary["segment_rule"], "count");

    const auto text = run_smb(folder, {"run", "-n", "1000", "-s", "3", "--pipeline", "paper"});
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("list sort"), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("quantiles"), std::string::npos) << text.out;
}

TEST(CliRun, PaperSegmentRuleIsChosenAndChecked) {
    TempFolder folder;
    const auto result =
        run_smb(folder, {"run", "-n", "2000", "-s", "3", "--pipeline", "paper", "--segment-rule", "paper", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["segment_rule"], "paper");
    EXPECT_EQ(summary["oversized_boxes_last"], 0);
    EXPECT_TRUE(summary["check"]["ok"].get<bool>());
    const auto& counts = summary["counts_median"];
    EXPECT_GT(counts["cells"].get<double>(), 0);
    EXPECT_GT(counts["largest_cell_boxes"].get<double>(), 0);
    for (const char* axis : {"z", "y", "x"}) {
        EXPECT_GT(counts["levels"][axis]["sort_comparisons"].get<double>(), 0) << axis;
    }
}

TEST(CliRun, CheckEveryK2d) {
    TempFolder folder;
    const auto result =
        run_smb(folder, {"run", "--dim", "2", "-n", "1500", "-s", "10", "--check-every", "3", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["dimension"], 2);
    EXPECT_EQ(summary["check"]["steps_checked"], 4);  // steps 3, 6, 9 and the last
    EXPECT_TRUE(summary["check"]["ok"].get<bool>());
}

TEST(CliRun, TextSummaryIsShortAndSaysOk) {
    TempFolder folder;
    const auto result = run_smb(folder, {"run", "-n", "1000", "-s", "5", "-L", "0.01"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_NE(result.out.find("build (step 1)"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("median"), std::string::npos);
    EXPECT_NE(result.out.find("bytes per box"), std::string::npos);
    EXPECT_NE(result.out.find("OK"), std::string::npos);
    EXPECT_LT(std::count(result.out.begin(), result.out.end(), '\n'), 12);
    EXPECT_TRUE(result.err.empty());  // no progress bar when standard error is not a terminal
}

TEST(CliRun, SingleStepAndNoCheck) {
    TempFolder folder;
    const auto result = run_smb(folder, {"run", "-n", "500", "-s", "1", "--no-check", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_TRUE(summary["detect_seconds"].is_null());
    EXPECT_FALSE(summary["check"]["enabled"].get<bool>());
}

TEST(CliRun, DetectorWithASkinChecksEveryStepAndSaysHowItKeptItsCandidates) {
    TempFolder folder;
    const auto result = run_smb(folder, {"run", "-n", "3000", "-s", "12", "-L", "1e-4", "--pipeline", "detector",
                                         "--skin", "0.1", "--check-every", "1", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["pipeline"], "detector");
    EXPECT_DOUBLE_EQ(summary["skin"].get<double>(), 0.1);
    EXPECT_EQ(summary["check"]["steps_checked"], 12);
    EXPECT_TRUE(summary["check"]["ok"].get<bool>());
    EXPECT_LT(summary["skin_steps"]["rebuilt"].get<std::size_t>(), 11U);
    EXPECT_GT(summary["skin_steps"]["candidates_median"].get<double>(), summary["pairs"]["median"].get<double>());
    // A detector takes its boxes whole: it has no updates to apply, and checks its array.
    EXPECT_EQ(summary["phase_seconds_median"]["update"].get<double>(), 0);
    EXPECT_GT(summary["phase_seconds_median"]["scan"].get<double>(), 0);
    EXPECT_GT(summary["phase_seconds_median"]["containment"].get<double>(), 0);

    const auto text = run_smb(folder, {"run", "-n", "1000", "-s", "4", "--pipeline", "detector", "--skin", "0.1"});
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("skin"), std::string::npos) << text.out;
    // The paper's lists keep no skin.
    const auto refused = run_smb(folder, {"run", "-n", "100", "-s", "2", "--pipeline", "paper", "--skin", "0.1"});
    EXPECT_NE(refused.status, 0);
    EXPECT_NE(refused.err.find("--pipeline persistent or detector"), std::string::npos) << refused.err;
    EXPECT_NE(run_smb(folder, {"run", "--pipeline", "detector", "--skin", "-1"}).status, 0);
}

TEST(CliRun, WorldWithASkinChecksEveryStepAndSaysHowItKeptItsCandidates) {
    TempFolder folder;
    const auto result = run_smb(
        folder, {"run", "-n", "3000", "-s", "12", "-L", "1e-4", "--skin", "0.1", "--check-every", "1", "--json"});
    ASSERT_EQ(result.status, 0) << result.err;
    const auto summary = nlohmann::json::parse(result.out);
    EXPECT_EQ(summary["pipeline"], "persistent");
    EXPECT_DOUBLE_EQ(summary["skin"].get<double>(), 0.1);
    EXPECT_EQ(summary["check"]["steps_checked"], 12);
    EXPECT_TRUE(summary["check"]["ok"].get<bool>());
    EXPECT_LT(summary["skin_steps"]["rebuilt"].get<std::size_t>(), 11U);
    EXPECT_GT(summary["skin_steps"]["candidates_median"].get<double>(), summary["pairs"]["median"].get<double>());
    EXPECT_GT(summary["phase_seconds_median"]["containment"].get<double>(), 0);
}

TEST(CliRun, BadArgumentsAreRejected) {
    TempFolder folder;
    EXPECT_NE(run_smb(folder, {"run", "--dim", "4"}).status, 0);
    EXPECT_NE(run_smb(folder, {"run", "-L", "1.5"}).status, 0);
    EXPECT_NE(run_smb(folder, {"run", "-s", "0"}).status, 0);
    EXPECT_NE(run_smb(folder, {}).status, 0);  // a subcommand is required
}

}  // namespace
}  // namespace smb::cli_test
