// SPDX-License-Identifier: MIT
#pragma once
// The checks of WorldSettings and DetectorSettings, over the DetectionSettings they share.

#include <cmath>
#include <cstddef>
#include <string>

#include "core/shortest_number.hpp"
#include "smb/errors.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

inline constexpr std::size_t kMaxThreads = 1024;

/// Throws ArgumentError naming the first field the two share that does not fit, as a field of
/// `settings_name` (the class the caller handed over: the message names what they wrote).
template <class Settings>
void check_shared_settings(const Settings& settings, const std::string& settings_name) {
    if (settings.target_cell_population == 0)
        throw ArgumentError(settings_name + "::target_cell_population must be at least 1");
    if (settings.pair_chunk_size == 0) throw ArgumentError(settings_name + "::pair_chunk_size must be at least 1");
    if (settings.threads > kMaxThreads)
        throw ArgumentError(settings_name + "::threads must be at most " + std::to_string(kMaxThreads) +
                            " (0: as many as OpenMP offers), not " + std::to_string(settings.threads));
    if (!(settings.skin >= 0) || !std::isfinite(settings.skin))
        throw ArgumentError(settings_name + "::skin must be finite and at least 0, not " +
                            shortest_number(settings.skin));
}

/// `settings`, or ArgumentError naming the first field that does not fit.
[[nodiscard]] inline WorldSettings validated_settings(const WorldSettings& settings) {
    check_shared_settings(settings, "WorldSettings");
    if (settings.pipeline != Pipeline::persistent_cuts && settings.pipeline != Pipeline::paper_lists)
        throw ArgumentError("WorldSettings::pipeline is not a known Pipeline");
    if (settings.segment_rule != SegmentRule::from_count && settings.segment_rule != SegmentRule::twice_largest_box)
        throw ArgumentError("WorldSettings::segment_rule is not a known SegmentRule");
    if (settings.skin > 0 && settings.pipeline == Pipeline::paper_lists)
        throw ArgumentError("WorldSettings::skin needs Pipeline::persistent_cuts (the paper's lists keep no skin)");
    return settings;
}

/// `settings`, or ArgumentError naming the first field that does not fit.
[[nodiscard]] inline DetectorSettings validated_settings(const DetectorSettings& settings) {
    check_shared_settings(settings, "DetectorSettings");
    return settings;
}

}  // namespace smb::detail
