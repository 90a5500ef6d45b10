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

/// The pipeline the world tests run: CTest runs each such test twice (tests/CMakeLists.txt),
/// once with SMB_TEST_PIPELINE=paper, so both pipelines are held to brute force.
inline Pipeline test_pipeline() {
    const char* chosen = std::getenv("SMB_TEST_PIPELINE");
    return chosen != nullptr && std::string_view(chosen) == "paper" ? Pipeline::paper_lists : Pipeline::persistent_cuts;
}

inline WorldSettings test_settings() {
    WorldSettings settings;
    settings.pipeline = test_pipeline();
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
