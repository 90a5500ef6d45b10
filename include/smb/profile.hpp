// SPDX-License-Identifier: MIT
#pragma once
// Where one detect() call spent its time and work, phase by phase and level by level: filled
// only when DetectionSettings::profile asks for it, so that a detection without it reads no
// clock but the one of DetectStats::total_seconds.

#include <array>
#include <cstddef>

namespace smb {

/// The last detection's phases and pipeline counts (World::last_profile(),
/// Detector::last_profile()); all zero unless DetectionSettings::profile is set. Times are
/// wall-clock seconds. The phases update, scan, containment, quantile, list_sort, cut_regroup and
/// check are disjoint; together they are DetectStats::total_seconds but for the bookkeeping
/// between them. A phase a path does not have stays zero there; a detection made class by
/// class (filters) or on a periodic domain reports the sums of its parts.
struct DetectProfile {
    /// World only: taking the boxes removed since the last detection out of the held lists;
    /// with filters or statics, gathering the moving boxes and indexing the statics; on a
    /// periodic domain, bringing the boxes into the domain and making their images.
    double update_seconds = 0;
    /// The pass over the boxes before the cuts (persistent cuts): the scene's bounds and the
    /// choice of held precision (floats or doubles), with a Detector's check of every box.
    double scan_seconds = 0;
    /// With a skin: checking every box against its fat box, and making new fat boxes for the
    /// boxes that left theirs (or arrived).
    double containment_seconds = 0;
    /// Persistent cuts: selecting the quantiles (the cut positions) of the groups cut again,
    /// on every level; where threads cut groups side by side, their seconds over the threads.
    double quantile_seconds = 0;
    /// Pipeline::paper_lists: the diminishing increment sorts (DIS) of every level's lists.
    double list_sort_seconds = 0;
    /// The rest of the axial cuts: placing every box in its segment on each level and
    /// regrouping the boxes by segment (persistent cuts, the copy in cell order included);
    /// merging the inserted boxes, regrouping, cutting and building each cell's lists
    /// (Pipeline::paper_lists).
    double cut_regroup_seconds = 0;
    /// Checking the cells (with the sorts of their sweeps), the oversized boxes, and reporting
    /// the pairs; with a skin, testing the candidates and finding those of the refreshed boxes.
    double check_seconds = 0;
    /// Persistent cuts, within quantile_seconds and cut_regroup_seconds: copy_seconds copied
    /// the boxes in last step's cell order, level_seconds[l] placed, cut again where needed
    /// and regrouped level l, whose axis is Dim - 1 - l (z, y, x in 3D; the third stays zero
    /// in 2D).
    double copy_seconds = 0;
    std::array<double, 3> level_seconds{};

    std::size_t cells = 0;            ///< cells made by the axial cuts (including empty ones)
    std::size_t oversized_boxes = 0;  ///< boxes spanning more than two segments on some axis
    /// Items moved by the sorts: the diminishing increment sorts of the lists
    /// (Pipeline::paper_lists), the insertion sorts inside the cells' sweeps (persistent cuts).
    std::size_t sort_moves = 0;

    /// Pipeline::paper_lists, per level l (axis Dim - 1 - l): items moved by the level's
    /// diminishing increment sorts; their key comparisons, counted as one per item per pass
    /// plus one per move (an upper bound by the items that reached the front of their
    /// section); the singular items, those whose parent item changed segment on the level
    /// above, so that the regrouping moved them to another section (zero on level 0; the boxes
    /// inserted since the last detection are not counted); and the items of the sections
    /// whose sort ran out of its move budget (8 moves per item in one pass) and was finished
    /// by introsort, whose comparisons are not counted.
    std::array<std::size_t, 3> level_sort_moves{};
    std::array<std::size_t, 3> level_sort_comparisons{};
    std::array<std::size_t, 3> level_singular_items{};
    std::array<std::size_t, 3> level_sort_fallback_items{};
    /// Pipeline::paper_lists: the most boxes any one cell held (the side of its flag matrix).
    std::size_t largest_cell_boxes = 0;
};

}  // namespace smb
