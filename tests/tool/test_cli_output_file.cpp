// SPDX-License-Identifier: MIT
// The tool's output files appear only when complete: written beside the target, renamed on
// commit, removed when abandoned.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "file_streams.hpp"

namespace smb::io {
namespace {

namespace fs = std::filesystem;

class OutputFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "smb-output-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        folder_ = pattern;
    }
    void TearDown() override { fs::remove_all(folder_); }

    static std::string contents(const fs::path& path) {
        std::ifstream in(path);
        std::ostringstream text;
        text << in.rdbuf();
        return text.str();
    }
    std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder_), {})); }

    fs::path folder_;
};

TEST_F(OutputFileTest, CommitMovesTheFileIntoPlace) {
    const fs::path target = folder_ / "pairs.csv";
    {
        OutputFile output(target.string());
        output.stream() << "frame,a,b\n";
        EXPECT_FALSE(fs::exists(target));
        output.commit();
    }
    EXPECT_EQ(contents(target), "frame,a,b\n");
    EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, AbandonedOutputLeavesNothing) {
    const fs::path target = folder_ / "pairs.csv";
    {
        OutputFile output(target.string());
        output.stream() << "partial";
    }
    EXPECT_EQ(entries(), 0u);
}

TEST_F(OutputFileTest, AbandonedOutputKeepsThePreviousFile) {
    const fs::path target = folder_ / "pairs.csv";
    std::ofstream(target) << "old\n";
    {
        OutputFile output(target.string());
        output.stream() << "new";
    }
    EXPECT_EQ(contents(target), "old\n");
    EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, MissingFolderIsAnError) {
    EXPECT_THROW(OutputFile((folder_ / "no-such-folder" / "x.csv").string()), std::runtime_error);
}

TEST_F(OutputFileTest, MissingInputIsAnErrorNamingThePath) {
    try {
        InputFile input((folder_ / "absent.csv").string());
        FAIL() << "no error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("absent.csv"), std::string::npos);
    }
    EXPECT_THROW(InputFile(folder_.string()), std::runtime_error);
}

}  // namespace
}  // namespace smb::io
