// SPDX-License-Identifier: MIT
#pragma once
// What one detect() call did and cost, in fields that mean one thing on every path. The
// pipelines' phases and inner counts are in the opt-in profile (smb/profile.hpp).

#include <cstddef>

namespace smb {

/// What one detect() call did and cost. A field whose part a detection does not use stays zero.
struct DetectStats {
    std::size_t boxes = 0;       ///< boxes in the world (or the detector's array) during this detection
    std::size_t pairs = 0;       ///< overlapping pairs reported
    std::size_t bytes_held = 0;  ///< heap bytes the world or detector holds after the call
    double total_seconds = 0;    ///< wall-clock seconds of the whole call

    /// With a skin (DetectorSettings::skin, WorldSettings::skin) and floats held: the candidate
    /// pairs kept after this detection, the boxes that left their fat box (or arrived) and
    /// found new candidates, and whether the candidates were rebuilt from scratch by the cuts.
    std::size_t skin_candidates = 0;
    std::size_t skin_refreshed = 0;
    bool skin_rebuilt = false;

    /// A World with static boxes (docs/filters.md): the static boxes its moving boxes hold in
    /// their caches, the moving boxes that left their fat box (or arrived) and asked the
    /// statics' grid again, and whether the statics were indexed again (they changed).
    std::size_t static_contacts = 0;
    std::size_t static_refreshed = 0;
    bool statics_rebuilt = false;
};

}  // namespace smb
