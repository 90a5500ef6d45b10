#pragma once
// The one check of WorldSettings that World and Detector share.

#include <cmath>
#include <cstddef>
#include <string>

#include "smb/errors.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

inline constexpr std::size_t kMaxThreads = 1024;

/// `settings`, or ArgumentError naming the first field that does not fit.
[[nodiscard]] inline WorldSettings validated_settings(const WorldSettings& settings) {
    if (settings.target_cell_population == 0)
        throw ArgumentError("WorldSettings::target_cell_population must be at least 1");
    if (settings.pair_chunk_size == 0) throw ArgumentError("WorldSettings::pair_chunk_size must be at least 1");
    if (settings.pipeline != Pipeline::persistent_cuts && settings.pipeline != Pipeline::paper_lists)
        throw ArgumentError("WorldSettings::pipeline is not a known Pipeline");
    if (settings.threads > kMaxThreads)
        throw ArgumentError("WorldSettings::threads must be at most " + std::to_string(kMaxThreads) +
                            " (0: as many as OpenMP offers), not " + std::to_string(settings.threads));
    if (!(settings.skin >= 0) || !std::isfinite(settings.skin))
        throw ArgumentError("WorldSettings::skin must be finite and at least 0");
    return settings;
}

}  // namespace smb::detail
