// SPDX-License-Identifier: MIT
// Settings that belong to each class: WorldSettings (the pipeline) and DetectorSettings (the
// skin) share DetectionSettings; each is checked, and each error names the class it came in.

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "smb/smb.hpp"

namespace smb {
namespace {

template <class Settings>
concept HasPipeline = requires(Settings settings) {
    settings.pipeline;
};
template <class Settings>
concept HasSkin = requires(Settings settings) {
    settings.skin;
};

static_assert(std::is_base_of_v<DetectionSettings, WorldSettings>);
static_assert(std::is_base_of_v<DetectionSettings, DetectorSettings>);
static_assert(HasPipeline<WorldSettings> && HasSkin<WorldSettings>, "a World has a pipeline and a skin");
static_assert(HasSkin<DetectorSettings> && !HasPipeline<DetectorSettings>, "a Detector has one pipeline");
static_assert(!std::is_constructible_v<World3d, DetectorSettings>);
static_assert(!std::is_constructible_v<Detector3d, WorldSettings>);
static_assert(std::is_same_v<decltype(std::declval<const Detector3d&>().settings()), const DetectorSettings&>);
static_assert(std::is_same_v<decltype(std::declval<const World3d&>().settings()), const WorldSettings&>);

/// The message of the ArgumentError that making `Made` from `settings` throws, or "" if none.
template <class Made, class Settings>
std::string refusal(const Settings& settings) {
    try {
        Made made(settings);
    } catch (const ArgumentError& error) {
        return error.what();
    }
    return {};
}

TEST(Settings, DefaultsAreTheSameSharedSettingsForBoth) {
    const WorldSettings world;
    const DetectorSettings detector;
    EXPECT_EQ(world.target_cell_population, detector.target_cell_population);
    EXPECT_EQ(world.pair_chunk_size, detector.pair_chunk_size);
    EXPECT_EQ(world.max_pairs_held, detector.max_pairs_held);
    EXPECT_EQ(world.threads, detector.threads);
    EXPECT_EQ(world.pipeline, Pipeline::persistent_cuts);
    EXPECT_EQ(detector.skin, 0.0);
}

TEST(Settings, EachClassKeepsItsOwn) {
    DetectorSettings skinned;
    skinned.skin = 0.25;
    skinned.threads = 2;
    const Detector3d detector(skinned);
    EXPECT_EQ(detector.settings().skin, 0.25);
    EXPECT_EQ(detector.settings().threads, 2U);

    WorldSettings paper;
    paper.pipeline = Pipeline::paper_lists;
    paper.target_cell_population = 7;
    const World2d world(paper);
    EXPECT_EQ(world.settings().pipeline, Pipeline::paper_lists);
    EXPECT_EQ(world.settings().target_cell_population, 7U);
}

TEST(Settings, ErrorsNameTheClassTheSettingCameIn) {
    WorldSettings world;
    world.threads = 5000;
    EXPECT_NE(refusal<World3d>(world).find("WorldSettings::threads"), std::string::npos) << refusal<World3d>(world);
    DetectorSettings detector;
    detector.threads = 5000;
    EXPECT_NE(refusal<Detector3d>(detector).find("DetectorSettings::threads"), std::string::npos)
        << refusal<Detector3d>(detector);

    world = {};
    world.target_cell_population = 0;
    EXPECT_NE(refusal<World3f>(world).find("WorldSettings::target_cell_population"), std::string::npos);
    detector = {};
    detector.pair_chunk_size = 0;
    EXPECT_NE(refusal<Detector2f>(detector).find("DetectorSettings::pair_chunk_size"), std::string::npos);

    world = {};
    world.pipeline = static_cast<Pipeline>(7);
    EXPECT_NE(refusal<World2d>(world).find("WorldSettings::pipeline"), std::string::npos);
    world = {};
    world.segment_rule = static_cast<SegmentRule>(5);
    EXPECT_NE(refusal<World3d>(world).find("WorldSettings::segment_rule"), std::string::npos);
    detector = {};
    detector.skin = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(refusal<Detector2d>(detector).find("DetectorSettings::skin"), std::string::npos);
    world = {};
    world.skin = -1;
    EXPECT_NE(refusal<World3d>(world).find("WorldSettings::skin"), std::string::npos);
    world.skin = 0.5;
    world.pipeline = Pipeline::paper_lists;  // the paper's lists keep no skin
    EXPECT_NE(refusal<World3d>(world).find("WorldSettings::skin needs Pipeline::persistent_cuts"), std::string::npos);
}

TEST(Settings, MessagesWriteNumbersAsTheCallerWouldWriteThem) {
    DetectorSettings detector;
    detector.skin = -0.1;
    const std::string message = refusal<Detector3d>(detector);
    EXPECT_NE(message.find("not -0.1"), std::string::npos) << message;
    EXPECT_EQ(message.find("-0.100000"), std::string::npos) << message;

    World3d world;
    try {
        world.insert(5, Box3d{{0, 0.1, 0}, {1, 0.05, 1}});
        ADD_FAILURE() << "an inverted box was accepted";
    } catch (const InvalidBoxError& error) {
        EXPECT_NE(std::string(error.what()).find("ymin 0.1 > ymax 0.05"), std::string::npos) << error.what();
    }
}

TEST(Settings, ThePairLimitErrorNamesTheClassTheLimitCameIn) {
    const std::vector<Box3d> same(50, Box3d{{0, 0, 0}, {1, 1, 1}});  // 1225 pairs
    std::vector<Pair> pairs;
    WorldSettings world_settings;
    world_settings.max_pairs_held = 10;
    World3d world(world_settings);
    world.assign(same);
    try {
        world.detect(pairs);
        ADD_FAILURE() << "no PairLimitError";
    } catch (const PairLimitError& error) {
        EXPECT_NE(std::string(error.what()).find("WorldSettings::max_pairs_held"), std::string::npos) << error.what();
    }
    DetectorSettings detector_settings;
    detector_settings.max_pairs_held = 10;
    Detector3d detector(detector_settings);
    try {
        detector.detect(same, pairs);
        ADD_FAILURE() << "no PairLimitError";
    } catch (const PairLimitError& error) {
        EXPECT_NE(std::string(error.what()).find("DetectorSettings::max_pairs_held"), std::string::npos)
            << error.what();
    }
}

}  // namespace
}  // namespace smb
