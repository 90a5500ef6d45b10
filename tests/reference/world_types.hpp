// SPDX-License-Identifier: MIT
#pragma once
// The four instantiations of smb::World that typed tests run over, with readable names.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <string>
#include <string_view>

#include "smb/world.hpp"

namespace smb::test {

using WorldTypes = ::testing::Types<World2f, World2d, World3f, World3d>;

/// The value of SMB_TEST_PIPELINE, empty when unset.
inline std::string_view chosen_test_pipeline() {
    const char* chosen = std::getenv("SMB_TEST_PIPELINE");
    return chosen != nullptr ? std::string_view(chosen) : std::string_view();
}

/// The pipeline the world tests run: CTest runs each such test again with SMB_TEST_PIPELINE=paper
/// (tests/CMakeLists.txt), and some of them with SMB_TEST_PIPELINE=paper-rule (the paper's
/// lists with the paper's segment rule), so every pipeline is held to brute force.
inline Pipeline test_pipeline() {
    const std::string_view chosen = chosen_test_pipeline();
    return chosen == "paper" || chosen == "paper-rule" ? Pipeline::paper_lists : Pipeline::persistent_cuts;
}

inline WorldSettings test_settings() {
    WorldSettings settings;
    settings.pipeline = test_pipeline();
    if (chosen_test_pipeline() == "paper-rule") settings.segment_rule = SegmentRule::twice_largest_box;
    return settings;
}

struct WorldTypeNames {
    template <typename WorldType>
    static std::string GetName(int) {
        const std::string real = sizeof(typename WorldType::real_type) == sizeof(float) ? "f" : "d";
        return "World" + std::to_string(WorldType::dimension) + real;
    }
};

/// Smaller scenes when the tests run under sanitizers (tests/CMakeLists.txt defines the macro
/// for SMB_SANITIZE builds), so that the instrumented suite stays within minutes.
#if defined(SMB_TEST_REDUCED)
inline constexpr std::size_t kScaleDivisor = 4;
#else
inline constexpr std::size_t kScaleDivisor = 1;
#endif

inline constexpr std::size_t scaled(std::size_t count) { return count / kScaleDivisor > 0 ? count / kScaleDivisor : 1; }

}  // namespace smb::test
