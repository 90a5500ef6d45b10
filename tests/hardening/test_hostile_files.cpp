// SPDX-License-Identifier: MIT
// Hostile scene files for `smb pairs`, beyond the malformed cases of test_cli_pairs.cpp (empty
// file, unknown header, too few fields, text in a number, NaN, infinity, min > max, duplicate
// id, frames out of order, negative and too large integers). Every rejected file must give exit
// status 1 and a message naming the file and the line, never a crash; every accepted oddity
// (extreme but valid numbers, the largest id) must give the exact pairs.

#include <gtest/gtest.h>

#include <string>

#include "tool/test_cli_support.hpp"

namespace smb::cli_test {
namespace {

constexpr const char* header_2d = "frame,id,xmin,ymin,xmax,ymax\n";
constexpr const char* header_3d = "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n";

struct HostileScene {
    const char* name;
    std::string text;
    int line;
    const char* words;
};

class HostileFilesRejected : public ::testing::TestWithParam<HostileScene> {};

TEST_P(HostileFilesRejected, ExitOneNamingFileAndLine) {
    const HostileScene& hostile = GetParam();
    TempFolder folder;
    write_file(folder / "scene.csv", hostile.text);
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "pairs.csv"});
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_NE(result.err.find("scene.csv:" + std::to_string(hostile.line) + ": "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(hostile.words), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(folder / "pairs.csv"));
}

const std::string good_2d = std::string(header_2d) + "0,1,0,0,1,1\n";

std::string long_line(std::size_t length) { return std::string(length, '7'); }

INSTANTIATE_TEST_SUITE_P(
    EveryHostileCase, HostileFilesRejected,
    ::testing::Values(
        HostileScene{"ExtraColumn", good_2d + "1,1,0,0,1,1,9\n", 3, "expected 6 fields, found 7"},
        HostileScene{"TrailingComma", good_2d + "1,1,0,0,1,1,\n", 3, "expected 6 fields, found 7"},
        HostileScene{"Row3dUnder2dHeader", good_2d + "1,1,0,0,0,1,1,1\n", 3, "expected 6 fields"},
        HostileScene{"Row2dUnder3dHeader", std::string(header_3d) + "0,1,0,0,1,1\n", 2, "expected 8 fields"},
        HostileScene{"HeaderWithExtraColumn", "frame,id,xmin,ymin,xmax,ymax,mass\n0,1,0,0,1,1,1\n", 1,
                     "unknown header"},
        HostileScene{"HeaderInOtherCase", "FRAME,ID,XMIN,YMIN,XMAX,YMAX\n", 1, "unknown header"},
        HostileScene{"OnlyAByteOrderMark", "\xEF\xBB\xBF", 1, "unknown header"},
        HostileScene{"WhitespaceOnly", "  \n\n", 1, "unknown header"},
        HostileScene{"IdOneAbove64Bits", good_2d + "1,18446744073709551616,0,0,1,1\n", 3, "does not fit in 64 bits"},
        HostileScene{"FrameOver64Bits", good_2d + "99999999999999999999999,1,0,0,1,1\n", 3, "does not fit in 64 bits"},
        HostileScene{"NegativeZeroId", good_2d + "1,-0,0,0,1,1\n", 3, "negative"},
        HostileScene{"PlusSignedId", good_2d + "1,+1,0,0,1,1\n", 3, "not an unsigned integer"},
        HostileScene{"FractionalId", good_2d + "1,1.0,0,0,1,1\n", 3, "not an unsigned integer"},
        HostileScene{"EmptyField", good_2d + "1,1,,0,1,1\n", 3, "empty xmin"},
        HostileScene{"NumberOverflowsDouble", good_2d + "1,1,0,0,1e400,1\n", 3, "too large for a double"},
        HostileScene{"NegativeInfinityWord", good_2d + "1,1,-infinity,0,1,1\n", 3, "not finite"},
        HostileScene{"DoubleSign", good_2d + "1,1,+-1,0,1,1\n", 3, "not a number"},
        HostileScene{"HexFloat", good_2d + "1,1,0x1p3,0,9,1\n", 3, "not a number"},
        HostileScene{"DecimalComma", good_2d + "1,1,0;5,0,1,1\n", 3, "not a number"},
        HostileScene{"NulByteInANumber", good_2d + std::string("1,1,0\0,0,1,1\n", 13), 3,
                     "xmin '0\\x00' is not a number"},
        HostileScene{"BinaryGarbage", good_2d + std::string("\x01\xff\xfe\x80,\x00\x7f\n", 8), 3,
                     "expected 6 fields, found 2"},
        HostileScene{"TenMegabyteLineWithoutNewline", good_2d + long_line(10u << 20), 3, "expected 6 fields, found 1"},
        HostileScene{"TenMegabyteNumber", good_2d + "1,1,0,0,1," + long_line(10u << 20) + "\n", 3,
                     "too large for a double"},
        HostileScene{"MinAboveMaxInZ", std::string(header_3d) + "0,1,0,0,2,1,1,1\n", 2,
                     "zmin 2 is greater than zmax 1"},
        HostileScene{"DuplicateIdAfterOtherIds", good_2d + "1,5,0,0,1,1\n1,3,0,0,1,1\n1,9,0,0,1,1\n1,5,2,2,3,3\n", 6,
                     "appears twice"},
        HostileScene{"FrameGoesBackAfterASkip", good_2d + "7,1,0,0,1,1\n5,1,0,0,1,1\n", 4, "frames must not decrease"}),
    [](const auto& instance) { return std::string(instance.param.name); });

struct OddButValidScene {
    const char* name;
    std::string text;
    std::string pairs;
};

class HostileFilesAccepted : public ::testing::TestWithParam<OddButValidScene> {};

TEST_P(HostileFilesAccepted, ExactPairs) {
    const OddButValidScene& odd = GetParam();
    TempFolder folder;
    write_file(folder / "scene.csv", odd.text);
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "-"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, "frame,a,b\n" + odd.pairs);
}

INSTANTIATE_TEST_SUITE_P(
    EveryOddCase, HostileFilesAccepted,
    ::testing::Values(OddButValidScene{"LargestIdTouchingSmallest",
                                       std::string(header_2d) + "0,18446744073709551615,1,1,2,2\n0,0,0,0,1,1\n",
                                       "0,0,18446744073709551615\n"},
                      OddButValidScene{"SubnormalAndNegativeZeroTouch",
                                       std::string(header_2d) + "0,1,-1,-1,-0,-0\n0,2,0,0,4.9e-324,1\n"
                                                                "0,3,4.9e-324,0,1,1\n",
                                       "0,1,2\n0,2,3\n"},
                      OddButValidScene{"LargestFiniteCoordinates",
                                       std::string(header_2d) +
                                           "0,1,-1.7976931348623157e308,-1.7976931348623157e308,"
                                           "1.7976931348623157e308,1.7976931348623157e308\n"
                                           "0,2,1.7976931348623157e308,0,1.7976931348623157e308,0\n"
                                           "0,3,1e308,1e308,1e308,1e308\n",
                                       "0,1,2\n0,1,3\n"},
                      OddButValidScene{"UnderflowingNumberBecomesZero",
                                       std::string(header_2d) + "0,1,1e-400,0,1,1\n0,2,-1,-1,0,0\n", "0,1,2\n"},
                      OddButValidScene{"CrlfBlankLinesNoFinalNewline",
                                       std::string("frame,id,xmin,ymin,xmax,ymax\r\n\r\n0,1,0,0,1,1\r\n"
                                                   "0,2,1,1,2,2\r\n\r\n3,1,0,0,1,1\r\n3,2,5,5,6,6"),
                                       "0,1,2\n"},
                      OddButValidScene{"ZeroSizedBoxesAtOnePoint",
                                       std::string(header_3d) + "0,4,1,1,1,1,1,1\n0,2,1,1,1,1,1,1\n"
                                                                "0,3,1,1,1,1,1,1\n",
                                       "0,2,3\n0,2,4\n0,3,4\n"},
                      OddButValidScene{"ManyEmptyFramesSkipped",
                                       std::string(header_2d) + "0,1,0,0,1,1\n0,2,0,0,1,1\n"
                                                                "18446744073709551615,1,0,0,1,1\n"
                                                                "18446744073709551615,2,0,0,1,1\n",
                                       "0,1,2\n18446744073709551615,1,2\n"}),
    [](const auto& instance) { return std::string(instance.param.name); });

// A pair explosion: every box of a frame overlaps every other. With a small allowance the frame
// is sorted through temporary files and must still come out exact and in order.
TEST(HostileFiles, PairExplosionIsSortedThroughTemporaryFiles) {
    constexpr int box_count = 300;  // 44 850 pairs
    std::string scene = header_3d;
    std::string expected = "frame,a,b\n";
    for (int frame = 0; frame < 2; ++frame) {
        for (int id = box_count - 1; id >= 0; --id)
            scene += std::to_string(frame) + "," + std::to_string(id) + ",0,0,0,1,1,1\n";
        for (int a = 0; a < box_count; ++a)
            for (int b = a + 1; b < box_count; ++b)
                expected += std::to_string(frame) + "," + std::to_string(a) + "," + std::to_string(b) + "\n";
    }
    TempFolder folder;
    write_file(folder / "scene.csv", scene);
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "-o", "pairs.csv", "--pairs-in-memory", "1000"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(read_file(folder / "pairs.csv") == expected);
}

TEST(HostileFiles, PairsInMemoryBelowTwoIsRejected) {
    TempFolder folder;
    write_file(folder / "scene.csv", std::string(header_2d));
    const auto result = run_smb(folder, {"pairs", "-i", "scene.csv", "--pairs-in-memory", "1"});
    EXPECT_NE(result.status, 0);
    EXPECT_FALSE(result.err.empty());
}

}  // namespace
}  // namespace smb::cli_test
