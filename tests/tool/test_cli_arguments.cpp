// SPDX-License-Identifier: MIT
// What smb says and returns for bad arguments and for output it could not write: the exit
// statuses that `smb --help` states, the same as tools/smb/README.md states, are the ones it
// returns.

#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

// Plain string scans rather than <regex>: GCC 12's std::regex trips -Wmaybe-uninitialized in
// the sanitizer build, where warnings are errors.

/// The text with every run of white space (a line break included) made one space.
std::string collapsed(const std::string& text) {
    std::string out;
    bool in_space = false;
    for (const char c : text) {
        if (std::isspace(static_cast<unsigned char>(c)) != 0) {
            in_space = true;
            continue;
        }
        if (in_space) out += ' ';
        in_space = false;
        out += c;
    }
    if (in_space) out += ' ';
    return out;
}

/// The "Exit status: ..." sentence of `smb --help`.
std::string exit_status_sentence() {
    TempFolder folder;
    const auto help = run_smb(folder, {"--help"});
    EXPECT_EQ(help.status, 0) << help.err;
    const std::string text = collapsed(help.out);
    const std::size_t start = text.find("Exit status: ");
    if (start == std::string::npos) return {};
    const std::size_t end = text.find('.', start);
    if (end == std::string::npos) return {};
    return text.substr(start, end + 1 - start);
}

/// The status that `smb --help` gives for bad arguments.
int documented_usage_status() {
    const std::string sentence = exit_status_sentence();
    const std::size_t words = sentence.find(" bad arguments");
    if (words == std::string::npos) return -1;
    std::size_t first = words;
    while (first > 0 && std::isdigit(static_cast<unsigned char>(sentence[first - 1])) != 0) --first;
    if (first == words) return -1;
    return std::stoi(sentence.substr(first, words - first));
}

TEST(CliArguments, HelpAndReadmeStateTheSameExitStatuses) {
    const std::string sentence = exit_status_sentence();
    ASSERT_FALSE(sentence.empty());
    const std::string readme = collapsed(read_file(SMB_CLI_README));
    // The README quotes the sentence, possibly wrapped over lines and in backticks.
    EXPECT_NE(readme.find(sentence), std::string::npos) << sentence;
    EXPECT_NE(sentence.find("0 success"), std::string::npos);
    EXPECT_NE(sentence.find("1 bad input or I/O failure"), std::string::npos);
    EXPECT_NE(sentence.find("2 a checked step"), std::string::npos);
}

TEST(CliArguments, UnknownCommandIsNamedWithTheCommands) {
    const int usage = documented_usage_status();
    ASSERT_GT(usage, 2);
    TempFolder folder;
    const auto result = run_smb(folder, {"frobnicate"});
    EXPECT_EQ(result.status, usage);
    EXPECT_NE(result.err.find("unknown command 'frobnicate'"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("pairs, generate, run"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty());
}

TEST(CliArguments, EveryArgumentErrorGivesTheDocumentedStatus) {
    const int usage = documented_usage_status();
    ASSERT_GT(usage, 2);
    TempFolder folder;
    const std::vector<std::vector<std::string>> bad_arguments{
        {},                                                            // no command
        {"--frobnicate"},                                              // unknown option before the command
        {"pairs", "--frobnicate"},                                     // unknown option
        {"pairs", "--pairs-in-memory", "1"},                           // out of range
        {"pairs", "--input"},                                          // missing value
        {"generate", "--side", "20", "-E", "0.3"},                     // options that exclude each other
        {"generate", "-n", "many"},                                    // not a number
        {"run", "--dim", "4"},                                         // not one of the choices
        {"run", "-L", "1.5"},                                          // out of range
        {"run", "-n", "-5"},                                           // negative count
        {"run", "--threads", "2000"},                                  // beyond WorldSettings' 1024
        {"run", "-n", "100", "--pipeline", "paper", "--skin", "0.1"},  // checked once parsed: no skin there
        {"run", "--pipeline", "paper", "--segment-rule", "largest"},   // not one of the choices
        {"run", "-n", "100", "-s", "2", "--segment-rule", "paper"},    // needs the paper pipeline
    };
    for (const auto& arguments : bad_arguments) {
        const auto result = run_smb(folder, arguments);
        std::string shown;
        for (const auto& argument : arguments) shown += argument + ' ';
        EXPECT_EQ(result.status, usage) << shown << '\n' << result.err;
        EXPECT_TRUE(result.err.starts_with("smb: error: ")) << shown << '\n' << result.err;
        EXPECT_NE(result.err.find("--help"), std::string::npos) << shown << '\n' << result.err;
    }
}

TEST(CliArguments, HelpAndVersionSucceed) {
    TempFolder folder;
    for (const auto& arguments : std::vector<std::vector<std::string>>{
             {"--help"}, {"--version"}, {"pairs", "--help"}, {"generate", "--help"}, {"run", "--help"}}) {
        const auto result = run_smb(folder, arguments);
        EXPECT_EQ(result.status, 0) << arguments.front() << '\n' << result.err;
        EXPECT_FALSE(result.out.empty());
    }
}

TEST(CliArguments, PairsHelpDescribesTheFormats) {
    TempFolder folder;
    const auto help = run_smb(folder, {"pairs", "--help"});
    ASSERT_EQ(help.status, 0) << help.err;
    EXPECT_NE(help.out.find("frame,id,xmin,ymin,zmin,xmax,ymax,zmax"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("frame,id,xmin,ymin,xmax,ymax"), std::string::npos);
    EXPECT_NE(help.out.find("frame,a,b"), std::string::npos);
    EXPECT_NE(help.out.find("Exit status:"), std::string::npos);
}

// Standard output that cannot be written (here /dev/full: every write fails with ENOSPC) is a
// failed run, whichever command printed.
TEST(CliArguments, UnwritableStandardOutputFailsEveryCommand) {
    if (!fs::is_character_file("/dev/full")) GTEST_SKIP() << "no /dev/full";
    TempFolder folder;
    write_file(folder / "scene.csv", "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n0,2,0,0,1,1\n");
    const std::vector<std::vector<std::string>> commands{
        {"run", "-n", "200", "-s", "2"},
        {"run", "-n", "200", "-s", "2", "--json"},
        {"run", "-n", "200", "-s", "1", "--no-check", "--pipeline", "detector"},
        {"pairs", "-i", "scene.csv"},
        {"generate", "-n", "50", "-s", "2"},
        {"--help"},
        {"run", "--help"},
        {"--version"},
    };
    for (const auto& arguments : commands) {
        const auto result = run_smb_with(folder, arguments, {}, "/dev/full");
        std::string shown;
        for (const auto& argument : arguments) shown += argument + ' ';
        EXPECT_EQ(result.status, 1) << shown << '\n' << result.err;
        EXPECT_NE(result.err.find("smb: error: writing to standard output failed"), std::string::npos) << shown << '\n'
                                                                                                       << result.err;
    }
}

}  // namespace
}  // namespace smb::cli_test
