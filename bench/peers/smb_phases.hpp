// SPDX-License-Identifier: MIT
#pragma once
// Where an smb peer's detect() calls spent their time (DetectProfile), summed over the steps
// after the build and written as the smb_* fields of the peer's JSON. The World and Detector
// peers both run profiled, so that their steps pay the same few clock reads.

#include <cstddef>
#include <sstream>
#include <string>

#include "smb/profile.hpp"
#include "smb/stats.hpp"

namespace smb::bench {

class SmbPhases {
public:
    void add(const DetectProfile& profile, const DetectStats& stats) {
        ++steps_;
        sum_.update_seconds += profile.update_seconds;
        sum_.scan_seconds += profile.scan_seconds;
        sum_.containment_seconds += profile.containment_seconds;
        sum_.quantile_seconds += profile.quantile_seconds;
        sum_.list_sort_seconds += profile.list_sort_seconds;
        sum_.cut_regroup_seconds += profile.cut_regroup_seconds;
        sum_.check_seconds += profile.check_seconds;
        sum_.copy_seconds += profile.copy_seconds;
        for (std::size_t level = 0; level < profile.level_seconds.size(); ++level)
            sum_.level_seconds[level] += profile.level_seconds[level];
        sum_.sort_moves += profile.sort_moves;
        sum_.cells = profile.cells;
        sum_.oversized_boxes = profile.oversized_boxes;
        total_seconds_ += stats.total_seconds;
        bytes_held_ = stats.bytes_held;
        skin_candidates_ = stats.skin_candidates;
    }

    /// The fields, averaged over the steps; empty before the first step.
    [[nodiscard]] std::string json() const {
        if (steps_ == 0) return {};
        const double n = static_cast<double>(steps_);
        std::ostringstream json;
        json << "\"smb_update_s\":" << sum_.update_seconds / n << ",\"smb_scan_s\":" << sum_.scan_seconds / n
             << ",\"smb_containment_s\":" << sum_.containment_seconds / n
             << ",\"smb_quantile_s\":" << sum_.quantile_seconds / n
             << ",\"smb_list_sort_s\":" << sum_.list_sort_seconds / n
             << ",\"smb_cut_regroup_s\":" << sum_.cut_regroup_seconds / n
             << ",\"smb_check_s\":" << sum_.check_seconds / n << ",\"smb_copy_s\":" << sum_.copy_seconds / n
             << ",\"smb_level_s\":[" << sum_.level_seconds[0] / n << ',' << sum_.level_seconds[1] / n << ','
             << sum_.level_seconds[2] / n << "],\"smb_detect_s\":" << total_seconds_ / n
             << ",\"smb_sort_moves\":" << static_cast<double>(sum_.sort_moves) / n << ",\"smb_cells\":" << sum_.cells
             << ",\"smb_oversized\":" << sum_.oversized_boxes << ",\"smb_bytes_held\":" << bytes_held_
             << ",\"smb_skin_candidates\":" << skin_candidates_;
        return json.str();
    }

private:
    DetectProfile sum_;
    double total_seconds_ = 0;
    std::size_t bytes_held_ = 0;
    std::size_t skin_candidates_ = 0;  // the skin list's, at the last step
    std::size_t steps_ = 0;
};

}  // namespace smb::bench
