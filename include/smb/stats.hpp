// SPDX-License-Identifier: MIT
#pragma once
// What one detect() call did and cost, in fields that mean one thing in every pipeline: a phase
// a pipeline does not have stays zero there.

#include <array>
#include <cstddef>

namespace smb {

/// What one detect() call did and cost. Times are wall-clock seconds of this call. The phases
/// update, scan, containment, quantile, list_sort, cut_regroup and check are disjoint; together
/// they are total_seconds but for the bookkeeping between them.
struct DetectStats {
    std::size_t boxes = 0;            ///< boxes in the world (or the detector's array) during this detection
    std::size_t pairs = 0;            ///< overlapping pairs reported
    std::size_t cells = 0;            ///< cells made by the axial cuts (including empty ones)
    std::size_t oversized_boxes = 0;  ///< boxes spanning more than two segments on some axis
    /// Items moved by the sorts of this detection: the diminishing increment sorts of the lists
    /// (Pipeline::paper_lists), the insertion sorts inside the cells' sweeps (persistent cuts).
    std::size_t sort_moves = 0;
    std::size_t bytes_held = 0;  ///< heap bytes the world or detector holds after the call

    /// Pipeline::paper_lists, per level l (whose axis is Dim - 1 - l: z, y, x in 3D; the third
    /// stays zero in 2D): items moved by the level's diminishing increment sorts; their key
    /// comparisons, counted as one per item per pass plus one per move (an upper bound by the
    /// items that reached the front of their section); and the singular items, those whose
    /// parent item changed segment on the level above, so that the regrouping moved them to
    /// another section (zero on level 0; the boxes inserted since the last detection are not
    /// counted); and the items of the sections whose sort ran out of its move budget (8 moves
    /// per item in one pass) and was finished by introsort, whose comparisons are not counted.
    /// Zero with the persistent cuts.
    std::array<std::size_t, 3> level_sort_moves{};
    std::array<std::size_t, 3> level_sort_comparisons{};
    std::array<std::size_t, 3> level_singular_items{};
    std::array<std::size_t, 3> level_sort_fallback_items{};
    /// Pipeline::paper_lists: the most boxes any one cell held (the side of its flag matrix).
    /// Zero with the persistent cuts.
    std::size_t largest_cell_boxes = 0;

    /// With a skin (DetectorSettings::skin, WorldSettings::skin): candidate pairs kept after this
    /// detection, boxes that left their fat box (or arrived) and found new candidates, and
    /// whether the candidates were rebuilt from scratch by the axial cuts. World with static
    /// boxes and no skin (docs/filters.md): the static copies its moving boxes hold, the moving boxes that
    /// left their fat box (or arrived) and asked the statics' grid again, and whether the
    /// statics were indexed again (they changed).
    std::size_t skin_candidates = 0;
    std::size_t skin_refreshed = 0;
    bool skin_rebuilt = false;

    /// World only: taking the boxes removed since the last detection out of the held lists
    /// (their slots are compacted). Insertions and moves need no pass of their own. Zero when
    /// nothing was removed, and always in a Detector.
    double update_seconds = 0;
    /// The pass over the boxes before the cuts (persistent cuts): the scene's bounds and the
    /// choice of held precision (floats or doubles). A Detector checks every box of its array in
    /// the same pass (InvalidBoxError); a World checked its boxes when they were inserted or
    /// updated. Zero with Pipeline::paper_lists, which holds the boxes as they are.
    double scan_seconds = 0;
    /// With a skin: checking every box against its fat box, and making new fat boxes
    /// for the boxes that left theirs (or arrived). Zero otherwise.
    double containment_seconds = 0;
    /// Persistent cuts: selecting the quantiles (the cut positions) of the groups cut again in
    /// this detection, on every level; zero in most steps after the first, and with
    /// Pipeline::paper_lists. Where threads cut groups side by side, their seconds of selection
    /// over the number of threads.
    double quantile_seconds = 0;
    /// Pipeline::paper_lists: the diminishing increment sorts (DIS) of the lists of every level
    /// (the boxes inserted since the last detection are sorted apart and merged in, within
    /// cut_regroup_seconds). Zero with the persistent cuts, which keep no sorted lists (their
    /// cells' sweeps sort inside check_seconds).
    double list_sort_seconds = 0;
    /// The rest of the axial cuts: placing every box in its segment on each level and
    /// regrouping the boxes by segment (persistent cuts, the copy in cell order included);
    /// merging the inserted boxes into the first level's list, regrouping each level's lists by
    /// the parent level, cutting them and building each cell's lists (Pipeline::paper_lists).
    /// Without quantile_seconds and list_sort_seconds.
    double cut_regroup_seconds = 0;
    /// Checking the cells (with the sorts of their sweeps), the oversized boxes, and reporting
    /// the pairs; with a skin, testing the candidates and finding those of the refreshed boxes.
    double check_seconds = 0;
    /// Where quantile_seconds and cut_regroup_seconds went (persistent cuts; zero with
    /// Pipeline::paper_lists): copy_seconds copied the boxes in last step's cell order,
    /// level_seconds[l] placed, cut again where needed and regrouped level l, whose axis is
    /// Dim - 1 - l (z, y, x in 3D; the third stays zero in 2D). Together they are the two
    /// fields' time but for the bookkeeping between them.
    double copy_seconds = 0;
    std::array<double, 3> level_seconds{};
    double total_seconds = 0;  ///< the whole call
};

}  // namespace smb
