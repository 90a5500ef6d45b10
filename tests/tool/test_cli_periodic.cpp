// SPDX-License-Identifier: MIT
// `smb pairs --periodic` end to end: the periodic pair CSV of random scenes whose boxes cross the
// domain's faces, against the brute force over the 3^D images; the option's errors.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <sstream>
#include <string>
#include <vector>

#include "reference/periodic_brute_force.hpp"
#include "scene_csv.hpp"
#include "test_cli_support.hpp"

namespace smb::cli_test {
namespace {

/// Id `k` of a scene with ids across the whole 64-bit range: the edges first (2^32 packed beside
/// an index reached the bit that marks translated boxes), then k times an odd constant.
BoxId wide_id(BoxId k) {
    constexpr BoxId edges[] = {7,
                               BoxId{1} << 32,
                               ~BoxId{0},
                               (BoxId{1} << 32) - 1,
                               BoxId{1} << 63,
                               (BoxId{1} << 63) - 1,
                               (BoxId{1} << 32) + 1,
                               BoxId{1} << 31,
                               0};
    return k < std::size(edges) ? edges[k] : k * 0x9E3779B97F4A7C15u;
}

/// A scene CSV of `frames` frames of boxes moving across [0, side) on every axis (centres wrapped
/// on the periodic ones), some removed and inserted between frames; ids from wide_id where `wide`.
template <int Dim>
std::string random_scene(test::Random& random, const PeriodicDomain<double, Dim>& domain, double side, int frames,
                         bool wide = false) {
    std::string text = Dim == 2 ? "frame,id,xmin,ymin,xmax,ymax\n" : "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n";
    std::vector<Box<double, Dim>> boxes;
    std::vector<BoxId> ids;
    for (BoxId id = 0; id < 150; ++id) {
        boxes.push_back(test::particle_box<double, Dim>(random, side, 0.3, 2.5));
        ids.push_back(wide ? wide_id(id) : id * 7);
    }
    for (int frame = 0; frame < frames; ++frame) {
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            text += fmt::format("{},{}", frame, ids[i]);
            for (int k = 0; k < Dim; ++k) text += fmt::format(",{}", boxes[i].min[k]);
            for (int k = 0; k < Dim; ++k) text += fmt::format(",{}", boxes[i].max[k]);
            text += '\n';
        }
        for (auto& box : boxes) box = test::moved(random, box, domain, 0.5, false);
        boxes.erase(boxes.begin() + frame);
        ids.erase(ids.begin() + frame);
        boxes.push_back(test::particle_box<double, Dim>(random, side, 0.3, 2.5));
        ids.push_back(wide ? wide_id(100000 + static_cast<BoxId>(frame)) : 100000 + static_cast<BoxId>(frame));
    }
    return text;
}

/// The periodic pair CSV the brute force gives for every frame of the scene.
template <int Dim>
std::string expected_csv(const std::string& scene, const PeriodicDomain<double, Dim>& domain) {
    std::istringstream in(scene);
    io::SceneReader reader(in, "scene");
    io::SceneFrame<Dim> frame;
    std::string text = Dim == 2 ? "frame,a,b,sx,sy\n" : "frame,a,b,sx,sy,sz\n";
    while (reader.read_frame(frame)) {
        for (const PeriodicPair& p : test::brute_force_periodic_pairs<double, Dim>(frame.boxes, frame.ids, domain)) {
            text += fmt::format("{},{},{},{},{}", frame.number, p.a, p.b, p.shift[0], p.shift[1]);
            if (Dim == 3) text += fmt::format(",{}", p.shift[2]);
            text += '\n';
        }
    }
    return text;
}

TEST(CliPeriodic, TwoDimensionsOneAxisPeriodic) {
    TempFolder folder;
    test::Random random(1);
    PeriodicDomain<double, 2> domain;
    domain.wrap(0, 0, 12);
    const std::string scene = random_scene<2>(random, domain, 12, 6);
    write_file(folder.path() / "scene.csv", scene);
    const auto result = run_smb(folder, {"pairs", "--periodic", "0:12,-", "--input", "scene.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, expected_csv<2>(scene, domain));
}

TEST(CliPeriodic, ThreeDimensionsEveryAxisPeriodic) {
    TempFolder folder;
    test::Random random(2);
    PeriodicDomain<double, 3> domain;
    for (int k = 0; k < 3; ++k) domain.wrap(k, -2, 8);
    const std::string scene = random_scene<3>(random, domain, 10, 5);
    // The boxes start in [0, 10), partly beyond the domain [-2, 8).
    write_file(folder.path() / "scene.csv", scene);
    const auto result =
        run_smb(folder, {"pairs", "--periodic", "-2:8,-2:8,-2:8", "-i", "scene.csv", "-o", "pairs.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    const std::string written = read_file(folder.path() / "pairs.csv");
    EXPECT_EQ(written, expected_csv<3>(scene, domain));
    EXPECT_NE(written.find(",-1"), std::string::npos) << "no pair across the boundary";
}

TEST(CliPeriodic, IdsAcrossTheWholeRange) {
    TempFolder folder;
    // The three boxes of the report: (7, 2^32) was lost, or the run crashed without the third.
    write_file(folder.path() / "two.csv", "frame,id,xmin,ymin,xmax,ymax\n0,7,0,0,1,1\n0,4294967296,1,0,2,1\n");
    const auto two = run_smb(folder, {"pairs", "--periodic", "0:12,0:12", "-i", "two.csv", "-o", "two.out"});
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_EQ(read_file(folder.path() / "two.out"), "frame,a,b,sx,sy\n0,7,4294967296,0,0\n");
    write_file(folder.path() / "three.csv",
               "frame,id,xmin,ymin,xmax,ymax\n0,7,0,0,1,1\n0,4294967296,1,0,2,1\n"
               "0,18446744073709551615,11.5,0,12,1\n");
    const auto three = run_smb(folder, {"pairs", "--periodic", "0:12,0:12", "-i", "three.csv"});
    ASSERT_EQ(three.status, 0) << three.err;
    EXPECT_EQ(three.out, "frame,a,b,sx,sy\n0,7,4294967296,0,0\n0,7,18446744073709551615,-1,0\n");
    // Random scenes over frames, the ids spread over the range.
    test::Random random(3);
    PeriodicDomain<double, 3> domain;
    for (int k = 0; k < 3; ++k) domain.wrap(k, 0, 10);
    const std::string scene = random_scene<3>(random, domain, 10, 5, true);
    write_file(folder.path() / "scene.csv", scene);
    const auto result = run_smb(folder, {"pairs", "--periodic", "0:10,0:10,0:10", "-i", "scene.csv"});
    ASSERT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.out, expected_csv<3>(scene, domain));
    EXPECT_EQ(folder.entry_count(), 4u);  // the three scenes and two.out: no partial file left
}

TEST(CliPeriodic, BoundsAreDecimalNumbersAsInAScene) {
    TempFolder folder;
    write_file(folder.path() / "scene.csv", "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1e-321,1\n0,2,1e-321,0,2e-321,1\n");
    for (const std::string spec : {"0:0x3,-", "0:+3,-", "+0:3,-", "0x0:3,-", "0:3e,-", "0: 3 3,-"}) {
        const auto result = run_smb(folder, {"pairs", "--periodic", spec, "-i", "scene.csv"});
        EXPECT_EQ(result.status, 64) << spec << ": " << result.err;
        EXPECT_NE(result.err.find("--periodic"), std::string::npos) << result.err;
    }
    // Subnormal bounds are numbers like any other.
    const auto subnormal = run_smb(folder, {"pairs", "--periodic", "1e-320:2e-320,-", "-i", "scene.csv"});
    EXPECT_EQ(subnormal.status, 0) << subnormal.err;
    EXPECT_EQ(subnormal.out, "frame,a,b,sx,sy\n0,1,2,0,0\n");
    // A period that overflows is refused before any frame, its bounds in shortest form.
    const auto wide = run_smb(folder, {"pairs", "--periodic", "-1e308:1e308,-", "-i", "scene.csv"});
    EXPECT_EQ(wide.status, 64) << wide.err;
    EXPECT_NE(wide.err.find("-1e+308:1e+308"), std::string::npos) << wide.err;
    EXPECT_NE(wide.err.find("overflows"), std::string::npos) << wide.err;
    EXPECT_LT(wide.err.size(), 400u) << wide.err;
}

TEST(CliPeriodic, BadArgumentsExit64) {
    TempFolder folder;
    write_file(folder.path() / "scene.csv", "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n");
    for (const std::string spec :
         {"0:10", "0:10,0:10,0:10,0:10", "10:0,-", "0:x,-", "0:inf,-", "0-10,-", "0:10,nan:3"}) {
        const auto result = run_smb(folder, {"pairs", "--periodic", spec, "-i", "scene.csv"});
        EXPECT_EQ(result.status, 64) << spec << ": " << result.err;
        EXPECT_NE(result.err.find("--periodic"), std::string::npos) << result.err;
    }
    // Three axes for a 2D scene.
    const auto mismatch = run_smb(folder, {"pairs", "--periodic", "0:10,0:10,0:10", "-i", "scene.csv"});
    EXPECT_EQ(mismatch.status, 64) << mismatch.err;
    EXPECT_NE(mismatch.err.find("2D"), std::string::npos) << mismatch.err;
    const auto with_events = run_smb(folder, {"pairs", "--periodic", "0:10,-", "--events", "-i", "scene.csv"});
    EXPECT_EQ(with_events.status, 64) << with_events.err;
}

TEST(CliPeriodic, ABoxTooLargeForTheDomainFails) {
    TempFolder folder;
    write_file(folder.path() / "scene.csv", "frame,id,xmin,ymin,xmax,ymax\n0,1,0,0,1,1\n1,1,0,0,6,1\n");
    const auto result = run_smb(folder, {"pairs", "--periodic", "0:10,-", "-i", "scene.csv", "-o", "out.csv"});
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("frame 1"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("half the period"), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(folder.path() / "out.csv"));
}

}  // namespace
}  // namespace smb::cli_test
