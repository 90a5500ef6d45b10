// SPDX-License-Identifier: MIT
#pragma once
// The one detection behind every front door (a Detector's array, a World's store, a periodic
// detection's boxes and images, a filtered detection's classes): an array of boxes in, its
// overlapping pairs out. Once for all of them it checks the boxes and finds their bounds, chooses
// what to hold (floats where they resolve the scene, held_cut_pipeline.hpp), and detects with the
// persistent cuts or, given a skin, with the skin list (skin/skin_list.hpp), which steps aside to
// the cuts for a while when it does not pay. The skin list holds floats: a scene that floats do
// not resolve is detected by the cuts on doubles, skin or not.

#include <concepts>
#include <cstddef>
#include <span>

#include "core/scene_bounds.hpp"
#include "core/slot_renumbering.hpp"
#include "core/stopwatch.hpp"
#include "core/tuning.hpp"
#include "cuts/held_cut_pipeline.hpp"
#include "skin/skin_list.hpp"
#include "smb/box.hpp"
#include "smb/held_precision.hpp"
#include "smb/pair.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// The boxes of one detection, as the front door knows them.
template <std::floating_point Real, int Dim>
struct EngineInput {
    std::span<const Box<Real, Dim>> boxes;
    /// The name each box is reported under (keys[i] for box i); empty: its index.
    std::span<const BoxId> keys;
    /// Not null: the boxes are valid and these are their bounds (the periodic images).
    const SceneBounds<Real, Dim>* bounds = nullptr;
    /// The boxes are valid already (a World's store); their bounds are found only where the
    /// held floats need them.
    bool valid = false;
    /// keys[i] names the box the last detection saw at i, but at the slots fold_removals()
    /// moved and those past the last count (a World's store): the skin reads only those keys,
    /// and the cuts carry the others from one copy to the next (CellOrder::advance()).
    bool keys_kept = false;
};

template <std::floating_point Real, int Dim>
class DetectionEngine {
public:
    using box_type = Box<Real, Dim>;

    /// Reports every overlapping pair of `input` once, each as report(key_a, key_b) or in runs
    /// through report.append(). Throws InvalidBoxError (naming the index) before any change
    /// when a box of unchecked input is invalid. `skin` > 0 lets the skin list detect.
    /// Defined and compiled in engine/detection_engine.cpp, once per box type and report.
    template <class Report>
    void detect(const EngineInput<Real, Dim>& input, const DetectionSettings& settings, double skin, Report& report,
                DetectStats& stats, DetectProfile& profile);

    [[nodiscard]] HeldPrecision precision() const noexcept { return cuts_.precision(); }
    /// Pairs the held floats could not settle, tested again on the input, in the last detection.
    [[nodiscard]] std::size_t retested() const noexcept { return skin_detected_ ? skin_.retested() : cuts_.retested(); }
    /// Whether the skin list detected last; its candidates (skin_list()) are then current.
    [[nodiscard]] bool skin_detected() const noexcept { return skin_detected_; }
    [[nodiscard]] const SkinList<Real, Dim>& skin_list() const noexcept { return skin_; }

    /// Slots the next detection finds where it left them, which a World's compaction keeps in
    /// place (BoxStore::compact()). The skin list finds any box at any slot, and keeps its
    /// candidates best when the holes are filled from the end.
    [[nodiscard]] std::size_t listed(std::size_t slot_count) const noexcept {
        return skin_detected_ ? slot_count : cuts_.listed();
    }
    /// The slots in the order the cuts read them next (every slot once), where the cuts
    /// detected last; empty after the skin.
    [[nodiscard]] std::span<const Slot> suggested_order() const noexcept {
        return skin_detected_ ? std::span<const Slot>() : cuts_.order();
    }
    /// The caller renumbered its boxes by suggested_order(): slot p holds the box that was at
    /// suggested_order()[p].
    void follow_suggested_order() {
        if (!skin_detected_) cuts_.follow_own_order();
    }
    /// A World's store dropped removed slots and renumbered the others.
    void fold_removals(const SlotRenumbering& renumbering) {
        cuts_.fold_removals(renumbering);
        skin_.fold_removals(renumbering);
    }

    /// Forgets everything: the next detection starts afresh.
    void clear() {
        cuts_.clear();
        skin_.clear();
        skin_pause_ = 0;
        skin_detected_ = false;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept { return cuts_.bytes_held() + skin_.bytes_held(); }

private:
    /// With a skin, on floats: whether the skin list detected (detection_engine.cpp).
    template <class Report>
    bool detected_with_skin(const EngineInput<Real, Dim>& input, const SceneBounds<Real, Dim>& bounds,
                            const DetectionSettings& settings, double skin, Report& report, DetectStats& stats,
                            DetectProfile& profile);

    HeldCutPipeline<Real, Dim> cuts_;
    SkinList<Real, Dim> skin_;
    std::size_t skin_pause_ = 0;
    bool skin_detected_ = false;
};

}  // namespace smb::detail
