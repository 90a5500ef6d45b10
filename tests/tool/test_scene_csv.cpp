// SPDX-License-Identifier: MIT
// Reading and writing the scene CSV: both dimensions, tolerated variations (CRLF, no final
// newline, spaces, BOM), exact doubles, frame numbering, and every malformed case with its line.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "csv_error.hpp"
#include "scene_csv.hpp"

namespace smb::io {
namespace {

constexpr const char* header_3d = "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n";
constexpr const char* header_2d = "frame,id,xmin,ymin,xmax,ymax\n";

template <int Dim>
std::vector<SceneFrame<Dim>> read_all(const std::string& text) {
    std::istringstream in(text);
    SceneReader reader(in, "scene.csv");
    EXPECT_EQ(reader.dimension(), Dim);
    std::vector<SceneFrame<Dim>> frames;
    SceneFrame<Dim> frame;
    while (reader.read_frame(frame)) frames.push_back(frame);
    return frames;
}

/// Reads `text` to the end and expects a CsvError at `line` whose message contains `words`.
void expect_error(const std::string& text, std::uint64_t line, const std::string& words) {
    SCOPED_TRACE(text);
    try {
        std::istringstream in(text);
        SceneReader reader(in, "scene.csv");
        SceneFrame<3> frame3;
        SceneFrame<2> frame2;
        if (reader.dimension() == 3) {
            while (reader.read_frame(frame3)) {}
        } else {
            while (reader.read_frame(frame2)) {}
        }
        ADD_FAILURE() << "no error thrown";
    } catch (const CsvError& error) {
        EXPECT_EQ(error.line(), line);
        const std::string message = error.what();
        EXPECT_TRUE(message.starts_with("scene.csv:" + std::to_string(line) + ": ")) << message;
        EXPECT_NE(message.find(words), std::string::npos) << message;
    }
}

TEST(SceneCsv, Reads3dFramesSortedById) {
    const auto frames = read_all<3>(std::string(header_3d) +
                                    "0,5,0,0,0,1,1,1\n"
                                    "0,2,1.5,-2,3,4,5,6\n"
                                    "1,5,0.5,0,0,1,1,1\n");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].number, 0u);
    EXPECT_EQ(frames[0].ids, (std::vector<BoxId>{2, 5}));
    EXPECT_EQ(frames[0].boxes[0], (Box<double, 3>{{1.5, -2, 3}, {4, 5, 6}}));
    EXPECT_EQ(frames[0].lines, (std::vector<std::uint64_t>{3, 2}));
    EXPECT_EQ(frames[1].number, 1u);
    EXPECT_EQ(frames[1].boxes[0], (Box<double, 3>{{0.5, 0, 0}, {1, 1, 1}}));
}

TEST(SceneCsv, Reads2d) {
    const auto frames = read_all<2>(std::string(header_2d) + "4,1,0,1,2,3\n");
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].number, 4u);
    EXPECT_EQ(frames[0].boxes[0], (Box<double, 2>{{0, 1}, {2, 3}}));
}

TEST(SceneCsv, AcceptsCrlfAndNoFinalNewline) {
    const auto frames = read_all<2>("frame,id,xmin,ymin,xmax,ymax\r\n0,1,0,0,1,1\r\n0,2,0.5,0.5,2,2\r\n1,1,0,0,1,1.25");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].ids.size(), 2u);
    EXPECT_EQ(frames[1].boxes[0].max[1], 1.25);
}

TEST(SceneCsv, AcceptsByteOrderMarkSpacesAndBlankLines) {
    const auto frames = read_all<2>(
        "\xEF\xBB\xBF"
        "frame, id, xmin, ymin, xmax, ymax\n\n0, 1, 0 ,0,\t1,1\n\n");
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].boxes[0], (Box<double, 2>{{0, 0}, {1, 1}}));
}

TEST(SceneCsv, HeaderOnlyIsAnEmptyScene) {
    EXPECT_TRUE(read_all<3>(header_3d).empty());
    EXPECT_TRUE(read_all<3>("frame,id,xmin,ymin,zmin,xmax,ymax,zmax").empty());
}

TEST(SceneCsv, SkippedFrameNumbersAreNotReturned) {
    const auto frames = read_all<2>(std::string(header_2d) + "0,1,0,0,1,1\n3,1,0,0,1,1\n3,2,0,0,1,1\n");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].number, 0u);
    EXPECT_EQ(frames[1].number, 3u);
    EXPECT_EQ(frames[1].ids.size(), 2u);
}

TEST(SceneCsv, NegativeZeroEqualsZero) {
    const auto frames = read_all<2>(std::string(header_2d) + "0,1,-0.0,-0,0,0.0\n");
    ASSERT_EQ(frames.size(), 1u);
    const auto& box = frames[0].boxes[0];
    EXPECT_EQ(box.min[0], 0.0);
    EXPECT_TRUE(std::signbit(box.min[0]));
    EXPECT_TRUE(overlaps(box, Box<double, 2>{{0, 0}, {1, 1}}));
}

TEST(SceneCsv, ParsesToTheNearestDouble) {
    const std::vector<std::string> texts = {"0.1",
                                            "0.30000000000000001665",
                                            "2.2250738585072011e-308",
                                            "4.9e-324",
                                            "1e-400",
                                            "1.7976931348623157e308",
                                            "123456789012345678901234567890",
                                            "+2.5",
                                            "-7e-3",
                                            "9007199254740993",
                                            "0.1000000000000000055511151231257827021181583404541015625"};
    for (const auto& text : texts) {
        const auto frames = read_all<2>(std::string(header_2d) + "0,1," + text + ",0," + text + ",0\n");
        ASSERT_EQ(frames.size(), 1u) << text;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(frames[0].boxes[0].min[0]),
                  std::bit_cast<std::uint64_t>(std::strtod(text.c_str(), nullptr)))
            << text;
    }
}

TEST(SceneCsv, WriterRoundTripsEveryDoubleExactly) {
    std::mt19937_64 rng(42);
    std::vector<BoxId> ids;
    std::vector<Box<double, 3>> boxes;
    auto random_finite = [&rng] {
        for (;;) {
            const double value = std::bit_cast<double>(rng());
            if (std::isfinite(value)) return value;
        }
    };
    for (BoxId id = 0; id < 2000; ++id) {
        Box<double, 3> box;
        for (int k = 0; k < 3; ++k) {
            const double a = random_finite();
            const double b = random_finite();
            box.min[k] = std::min(a, b);
            box.max[k] = std::max(a, b);
        }
        ids.push_back(id * 0x9E3779B97F4A7C15ull);
        boxes.push_back(box);
    }
    boxes[0] = {{-0.0, 0.1, 1e-310}, {0.0, 0.2, std::numeric_limits<double>::max()}};

    std::ostringstream out;
    {
        SceneWriter writer(out, 3);
        writer.write_frame<3>(0, ids, boxes);
        writer.write_frame<3>(7, std::span(ids).first(1), std::span(boxes).first(1));
        writer.flush();
    }
    const auto frames = read_all<3>(out.str());
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[1].number, 7u);
    ASSERT_EQ(frames[0].ids.size(), ids.size());
    for (std::size_t row = 0; row < frames[0].ids.size(); ++row) {
        const auto original =
            static_cast<std::size_t>(std::find(ids.begin(), ids.end(), frames[0].ids[row]) - ids.begin());
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(std::bit_cast<std::uint64_t>(frames[0].boxes[row].min[k]),
                      std::bit_cast<std::uint64_t>(boxes[original].min[k]));
            ASSERT_EQ(std::bit_cast<std::uint64_t>(frames[0].boxes[row].max[k]),
                      std::bit_cast<std::uint64_t>(boxes[original].max[k]));
        }
    }
}

TEST(SceneCsv, WriterPrintsTheHeaderOfItsDimension) {
    std::ostringstream out;
    { SceneWriter writer(out, 2); }
    EXPECT_EQ(out.str(), header_2d);
}

TEST(SceneCsvErrors, EmptyFile) { expect_error("", 1, "empty file"); }

TEST(SceneCsvErrors, UnknownHeader) {
    expect_error("frame,id,x,y\n0,1,0,0\n", 1, "unknown header");
    expect_error("id,frame,xmin,ymin,xmax,ymax\n", 1, "unknown header");
}

TEST(SceneCsvErrors, WrongColumnCount) {
    expect_error(std::string(header_3d) + "0,1,0,0,0,1,1,1\n0,2,0,0,0,1,1\n", 3, "expected 8 fields, found 7");
    expect_error(std::string(header_2d) + "0,1,0,0,1,1,1\n", 2, "expected 6 fields, found 7");
}

TEST(SceneCsvErrors, TextInANumber) {
    expect_error(std::string(header_2d) + "0,1,0,abc,1,1\n", 2, "ymin 'abc' is not a number");
    expect_error(std::string(header_2d) + "0,1,0,1.5x,1,1\n", 2, "is not a number");
    expect_error(std::string(header_2d) + "0,1,0,+-1,1,1\n", 2, "is not a number");
    expect_error(std::string(header_2d) + "0,1,0,,1,1\n", 2, "empty ymin");
    expect_error(std::string(header_2d) + "0,x1,0,0,1,1\n", 2, "id 'x1' is not an unsigned integer");
    expect_error(std::string(header_2d) + "0.5,1,0,0,1,1\n", 2, "frame '0.5'");
}

TEST(SceneCsvErrors, NanAndInfinity) {
    expect_error(std::string(header_2d) + "0,1,0,0,1,1\n0,2,nan,0,1,1\n", 3, "xmin 'nan' is not finite");
    expect_error(std::string(header_2d) + "0,1,0,0,inf,1\n", 2, "is not finite");
    expect_error(std::string(header_2d) + "0,1,-infinity,0,1,1\n", 2, "is not finite");
    expect_error(std::string(header_2d) + "0,1,0,0,1e400,1\n", 2, "too large");
}

TEST(SceneCsvErrors, MinGreaterThanMax) {
    expect_error(std::string(header_3d) + "0,1,0,0,3,1,1,2\n", 2, "zmin 3 is greater than zmax 2");
}

TEST(SceneCsvErrors, DuplicateIdInAFrame) {
    expect_error(std::string(header_2d) + "0,1,0,0,1,1\n0,2,0,0,1,1\n0,1,0,0,1,1\n1,1,0,0,1,1\n", 4,
                 "id 1 appears twice in frame 0 (first on line 2)");
}

TEST(SceneCsvErrors, FramesOutOfOrder) {
    expect_error(std::string(header_2d) + "0,1,0,0,1,1\n2,1,0,0,1,1\n1,1,0,0,1,1\n", 4, "frame 1 comes after frame 2");
}

TEST(SceneCsvErrors, NegativeFrameAndId) {
    expect_error(std::string(header_2d) + "-1,1,0,0,1,1\n", 2, "frame '-1' is negative");
    expect_error(std::string(header_2d) + "0,-3,0,0,1,1\n", 2, "id '-3' is negative");
}

TEST(SceneCsvErrors, IdOverflow) {
    expect_error(std::string(header_2d) + "0,18446744073709551616,0,0,1,1\n", 2, "does not fit in 64 bits");
}

TEST(SceneCsvErrors, LineNumbersCountCrlfLinesAndBlankLines) {
    expect_error("frame,id,xmin,ymin,xmax,ymax\r\n0,1,0,0,1,1\r\n\r\n0,2,0,0,1\r\n", 4, "expected 6");
}

}  // namespace
}  // namespace smb::io
