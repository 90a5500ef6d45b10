// SPDX-License-Identifier: MIT
#pragma once
// Hands the changes of one environment step to a World through its batch calls.

#include <concepts>
#include <type_traits>
#include <vector>

#include "smb/workload/dynamic_environment.hpp"
#include "smb/world.hpp"

namespace smb::workload {

/// Converts environment boxes (double) to the world's coordinate type. Rounding to float may
/// make boxes that almost touch overlap or not; the reference must then be run on the same
/// converted boxes.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::vector<Box<Real, Dim>> convert_boxes(std::span<const Box<double, Dim>> boxes) {
    std::vector<Box<Real, Dim>> converted(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (int k = 0; k < Dim; ++k) {
            converted[i].min[k] = static_cast<Real>(boxes[i].min[k]);
            converted[i].max[k] = static_cast<Real>(boxes[i].max[k]);
        }
    }
    return converted;
}

/// Makes `world`, which held the environment as it was before the step, hold it as it is after:
/// removals, then updates, then insertions (whose ids are fresh). Apply env.changes() to an empty
/// world right after construction to load step 0.
template <std::floating_point Real, int Dim>
void apply_changes(const StepChanges<Dim>& changes, World<Real, Dim>& world) {
    if (!changes.removed_ids.empty()) world.remove(changes.removed_ids);
    if constexpr (std::is_same_v<Real, double>) {
        if (!changes.updated_ids.empty()) world.update(changes.updated_ids, changes.updated_boxes);
        if (!changes.inserted_ids.empty()) world.insert(changes.inserted_ids, changes.inserted_boxes);
    } else {
        if (!changes.updated_ids.empty()) world.update(changes.updated_ids, convert_boxes<Real>(changes.updated_boxes));
        if (!changes.inserted_ids.empty())
            world.insert(changes.inserted_ids, convert_boxes<Real>(changes.inserted_boxes));
    }
}

}  // namespace smb::workload
