// SPDX-License-Identifier: MIT
// Writing and reading the pair CSV: exact text, frames without contacts, and the checks of the
// reader (header, a < b, order).

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "csv_error.hpp"
#include "pair_csv.hpp"

namespace smb::io {
namespace {

std::vector<FramePair> read_text(const std::string& text) {
    std::istringstream in(text);
    return read_pair_csv(in, "pairs.csv");
}

void expect_error(const std::string& text, std::uint64_t line, const std::string& words) {
    SCOPED_TRACE(text);
    try {
        (void)read_text(text);
        ADD_FAILURE() << "no error thrown";
    } catch (const CsvError& error) {
        EXPECT_EQ(error.line(), line);
        EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
}

TEST(PairCsv, WritesHeaderAndRowsOfEachFrame) {
    std::ostringstream out;
    {
        PairWriter writer(out);
        const std::vector<Pair> first{{1, 2}, {1, 18446744073709551615ull}};
        const std::vector<Pair> none;
        const std::vector<Pair> third{{0, 3}};
        writer.write_frame(0, first);
        writer.write_frame(1, none);
        writer.write_frame(5, third);
        writer.flush();
    }
    EXPECT_EQ(out.str(), "frame,a,b\n0,1,2\n0,1,18446744073709551615\n5,0,3\n");
}

TEST(PairCsv, NoFramesGiveTheHeaderAlone) {
    std::ostringstream out;
    { PairWriter writer(out); }
    EXPECT_EQ(out.str(), "frame,a,b\n");
}

TEST(PairCsv, ReadsWhatItWrites) {
    std::ostringstream out;
    std::vector<FramePair> expected;
    {
        PairWriter writer(out);
        for (std::uint64_t frame = 0; frame < 50; frame += 3) {
            std::vector<Pair> pairs;
            for (BoxId a = 0; a < frame; ++a) pairs.push_back({a, a + frame + 1});
            writer.write_frame(frame, pairs);
            for (const Pair& pair : pairs) expected.push_back({frame, pair.a, pair.b});
        }
    }
    EXPECT_EQ(read_text(out.str()), expected);
}

TEST(PairCsv, ReadsCrlfWithoutFinalNewline) {
    EXPECT_EQ(read_text("frame,a,b\r\n0,1,2\r\n2,3,4"), (std::vector<FramePair>{{0, 1, 2}, {2, 3, 4}}));
}

TEST(PairCsv, ReaderRejectsMalformedFiles) {
    expect_error("", 1, "empty file");
    expect_error("frame,b,a\n", 1, "unknown header");
    expect_error("frame,a,b\n0,1\n", 2, "expected 3 fields, found 2");
    expect_error("frame,a,b\n0,2,1\n", 2, "a 2 is not less than b 1");
    expect_error("frame,a,b\n0,1,1\n", 2, "not less than");
    expect_error("frame,a,b\n1,1,2\n0,1,2\n", 3, "not sorted");
    expect_error("frame,a,b\n0,1,2\n0,1,2\n", 3, "repeat");
    expect_error("frame,a,b\n0,-1,2\n", 2, "negative");
}

}  // namespace
}  // namespace smb::io
