// SPDX-License-Identifier: MIT
// Replays every committed fuzz input through the checks of its libFuzzer target: the seed
// corpora (fuzz/corpus/<target>/) and the inputs that once broke something
// (fuzz/regressions/<target>/). A regression stays fixed in every build, not only under clang.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "detector_ops_check.hpp"
#include "scene_csv_check.hpp"
#include "world_ops_check.hpp"

namespace smb::test {
namespace {

namespace fs = std::filesystem;

/// Every file of fuzz/corpus/<target> and fuzz/regressions/<target>, in name order.
std::vector<fs::path> inputs_of(const std::string& target) {
    std::vector<fs::path> paths;
    for (const char* kind : {"corpus", "regressions"}) {
        const fs::path folder = fs::path(SMB_FUZZ_DIR) / kind / target;
        if (!fs::is_directory(folder)) continue;
        for (const auto& entry : fs::directory_iterator(folder))
            if (entry.is_regular_file()) paths.push_back(entry.path());
    }
    std::sort(paths.begin(), paths.end());
    return paths;
}

std::vector<std::uint8_t> bytes_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(HostileFuzzInputs, SceneCsvCorpusKeepsEveryPromise) {
    const auto paths = inputs_of("scene_csv");
    ASSERT_FALSE(paths.empty());
    for (const auto& path : paths) {
        const auto bytes = bytes_of(path);
        EXPECT_NO_THROW(fuzz::check_scene_csv(bytes.data(), bytes.size())) << path;
    }
}

TEST(HostileFuzzInputs, WorldOperationsCorpusKeepsEveryPromise) {
    const auto paths = inputs_of("world_ops");
    ASSERT_FALSE(paths.empty());
    for (const auto& path : paths) {
        const auto bytes = bytes_of(path);
        EXPECT_NO_THROW(fuzz::check_world_operations(bytes.data(), bytes.size())) << path;
    }
}

TEST(HostileFuzzInputs, DetectorOperationsCorpusKeepsEveryPromise) {
    const auto paths = inputs_of("detector_ops");
    ASSERT_FALSE(paths.empty());
    for (const auto& path : paths) {
        const auto bytes = bytes_of(path);
        EXPECT_NO_THROW(fuzz::check_detector_operations(bytes.data(), bytes.size())) << path;
    }
}

}  // namespace
}  // namespace smb::test
