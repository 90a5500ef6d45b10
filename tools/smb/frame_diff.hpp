// SPDX-License-Identifier: MIT
#pragma once
// What changed between two consecutive frames of a scene, in the shape of World's batch calls.

#include <span>
#include <vector>

#include "scene_csv.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::io {

template <int Dim>
struct FrameChanges {
    std::vector<BoxId> removed_ids;
    std::vector<BoxId> updated_ids;
    std::vector<Box<double, Dim>> updated_boxes;
    std::vector<BoxId> inserted_ids;
    std::vector<Box<double, Dim>> inserted_boxes;
};

/// Splits `frame` against the ids of the previous frame: ids only in the previous frame were
/// removed, ids only in `frame` inserted, the rest updated. Both id lists must be sorted, as
/// SceneReader returns them. Linear time (one merge).
template <int Dim>
void diff_frames(std::span<const BoxId> previous_ids, const SceneFrame<Dim>& frame, FrameChanges<Dim>& changes) {
    changes.removed_ids.clear();
    changes.updated_ids.clear();
    changes.updated_boxes.clear();
    changes.inserted_ids.clear();
    changes.inserted_boxes.clear();
    std::size_t p = 0;
    std::size_t c = 0;
    while (p < previous_ids.size() || c < frame.ids.size()) {
        if (c == frame.ids.size() || (p < previous_ids.size() && previous_ids[p] < frame.ids[c])) {
            changes.removed_ids.push_back(previous_ids[p++]);
        } else if (p == previous_ids.size() || frame.ids[c] < previous_ids[p]) {
            changes.inserted_ids.push_back(frame.ids[c]);
            changes.inserted_boxes.push_back(frame.boxes[c++]);
        } else {
            changes.updated_ids.push_back(frame.ids[c]);
            changes.updated_boxes.push_back(frame.boxes[c++]);
            ++p;
        }
    }
}

}  // namespace smb::io
