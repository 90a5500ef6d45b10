// SPDX-License-Identifier: MIT
#pragma once
// A detection made class by class (interaction_classes.hpp) reports the sums of its parts.

#include <cstddef>

#include "smb/stats.hpp"

namespace smb::detail {

/// Adds the work and the phase times of one class's detection to `total`.
inline void add_class_stats(DetectStats& total, const DetectStats& part) {
    total.cells += part.cells;
    total.oversized_boxes += part.oversized_boxes;
    total.sort_moves += part.sort_moves;
    total.skin_candidates += part.skin_candidates;
    total.skin_refreshed += part.skin_refreshed;
    total.skin_rebuilt = total.skin_rebuilt || part.skin_rebuilt;
    total.containment_seconds += part.containment_seconds;
    total.quantile_seconds += part.quantile_seconds;
    total.list_sort_seconds += part.list_sort_seconds;
    total.cut_regroup_seconds += part.cut_regroup_seconds;
    total.check_seconds += part.check_seconds;
    total.copy_seconds += part.copy_seconds;
    for (std::size_t l = 0; l < part.level_seconds.size(); ++l) total.level_seconds[l] += part.level_seconds[l];
}

}  // namespace smb::detail
