#pragma once

#include <array>
#include <cstddef>

namespace smb {

/// What one detect() call did and cost. Times are wall-clock seconds of this call.
struct DetectStats {
    std::size_t boxes = 0;            ///< boxes in the world during this detection
    std::size_t pairs = 0;            ///< overlapping pairs reported
    std::size_t cells = 0;            ///< cells made by the axial cuts (including empty ones)
    std::size_t oversized_boxes = 0;  ///< boxes spanning more than two segments on some axis
    std::size_t sort_moves = 0;       ///< items moved by the insertion/diminishing increment sorts
    std::size_t bytes_held = 0;       ///< heap bytes the world holds after the call

    /// Detector with a skin (WorldSettings::skin): candidate pairs kept after this detection,
    /// boxes that left their fat box (or arrived) and found new candidates, and whether the
    /// candidates were rebuilt from scratch by the axial cuts.
    std::size_t skin_candidates = 0;
    std::size_t skin_refreshed = 0;
    bool skin_rebuilt = false;

    double update_seconds = 0;         ///< applying insertions and removals to the lists
    /// Sorting: DIS on every level (Pipeline::paper_lists); selecting the quantiles of the
    /// groups cut again this step (Pipeline::persistent_cuts, zero in most steps). Where threads
    /// cut groups side by side, their seconds of selection over the number of threads.
    double sort_seconds = 0;
    double cut_regroup_seconds = 0;    ///< axial cuts, singular regrouping, per-cell lists
    double check_seconds = 0;          ///< cell checks (with their sorts), oversized boxes, reporting
    /// Where sort_seconds and cut_regroup_seconds went (Pipeline::persistent_cuts; zero
    /// elsewhere): copy_seconds copied the boxes in last step's cell order, level_seconds[l]
    /// located, cut again where needed and regrouped level l, whose axis is Dim - 1 - l (z, y, x
    /// in 3D; the third stays zero in 2D). Together they are the two phases' time but for the
    /// bookkeeping between them.
    double copy_seconds = 0;
    std::array<double, 3> level_seconds{};
    double total_seconds = 0;          ///< the whole call
};

}  // namespace smb
