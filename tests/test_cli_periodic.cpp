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

/// A scene CSV of `frames` frames of boxes moving across [0, side) on every axis (centres wrapped
/// on the periodic ones), some removed and inserted between frames.
template <int Dim>
std::string random_scene(test::Random& random, const PeriodicDomain<double, Dim>& domain, double side, int frames) {
    std::string text = Dim == 2 ? "frame,id,xmin,ymin,xmax,ymax\n" : "frame,id,xmin,ymin,zmin,xmax,ymax,zmax\n";
    std::vector<Box<double, Dim>> boxes;
    std::vector<BoxId> ids;
    for (BoxId id = 0; id < 150; ++id) {
        boxes.push_back(test::particle_box<double, Dim>(random, side, 0.3, 2.5));
        ids.push_back(id * 7);
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
        ids.push_back(100000 + static_cast<BoxId>(frame));
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
