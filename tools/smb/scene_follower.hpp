// SPDX-License-Identifier: MIT
#pragma once
// Keeps a World in step with a scene read one frame at a time.

#include <cstdint>
#include <vector>

#include "frame_diff.hpp"
#include "scene_csv.hpp"
#include "smb/box.hpp"

namespace smb::io {

/// Applies each frame of a scene to a World through its batch calls (the ids that left are
/// removed, those that stayed updated, the new ones inserted), so that the world keeps the
/// temporal coherence a simulation would give it. A frame number skipped after a present frame
/// is an empty frame: the world is emptied before the next present frame is applied.
template <int Dim>
class SceneFollower {
public:
    explicit SceneFollower(SceneReader& reader) : reader_(reader) {}

    /// Reads the next frame and applies it to `world`; false at the end of the scene. Where
    /// frame numbers jump, `on_skipped(first_skipped_number)` is called once the world is empty,
    /// for commands that report the empty frame.
    template <class WorldType, class OnSkipped>
    bool advance(WorldType& world, OnSkipped&& on_skipped) {
        if (!reader_.read_frame(frame_)) return false;
        if (!first_frame_ && frame_.number > previous_number_ + 1) {
            world.clear();
            previous_ids_.clear();
            on_skipped(previous_number_ + 1);
        }
        diff_frames<Dim>(previous_ids_, frame_, changes_);
        world.remove(changes_.removed_ids);
        world.update(changes_.updated_ids, changes_.updated_boxes);
        world.insert(changes_.inserted_ids, changes_.inserted_boxes);
        // The frame's ids are not needed past this point; its number and boxes stay readable.
        previous_ids_.swap(frame_.ids);
        previous_number_ = frame_.number;
        first_frame_ = false;
        return true;
    }

    template <class WorldType>
    bool advance(WorldType& world) {
        return advance(world, [](std::uint64_t) {});
    }

    /// The frame last applied.
    [[nodiscard]] std::uint64_t frame_number() const { return frame_.number; }

private:
    SceneReader& reader_;
    SceneFrame<Dim> frame_;
    FrameChanges<Dim> changes_;
    std::vector<BoxId> previous_ids_;
    bool first_frame_ = true;
    std::uint64_t previous_number_ = 0;
};

}  // namespace smb::io
