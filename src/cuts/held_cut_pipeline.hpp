// SPDX-License-Identifier: MIT
#pragma once
// The persistent-cut pipeline as a World or Detector of double boxes runs it: holding floats
// (held_box.hpp) wherever they resolve the scene, a copy of the doubles where they would not
// (scene_bounds.hpp judges). Floats halve the bytes every pass moves and double the boxes a
// vector compares at once. Float boxes are held as they are.

#include <array>
#include <cstddef>
#include <span>
#include <type_traits>

#include "core/assert.hpp"
#include "core/scene_bounds.hpp"
#include "core/slot_renumbering.hpp"
#include "core/tuning.hpp"
#include "cuts/persistent_cut_pipeline.hpp"
#include "smb/box.hpp"
#include "smb/held_precision.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class HeldCutPipeline {
public:
    /// Double input may be held as floats; float input is held as it is.
    static constexpr bool kMayRound = !std::is_same_v<Real, float>;

    [[nodiscard]] HeldPrecision precision() const noexcept { return precision_; }
    /// Where held floats start from (double input held as floats only).
    [[nodiscard]] std::array<Real, Dim> origin() const noexcept {
        if constexpr (kMayRound)
            return judgement_.origin;
        else
            return {};
    }
    /// Pairs the held floats could not settle, tested again on the input, in the last detection.
    [[nodiscard]] std::size_t retested() const noexcept { return retested_; }

    /// Chooses what the next detection of `boxes` (not empty), whose bounds are `bounds`, holds.
    /// Judges the scene again when it left the last judgement's region, when the number of boxes
    /// moved by more than a quarter (the cut counts change then anyway), and every
    /// tuning::judge_precision_every detections. A new origin forgets the cuts, so a scene still
    /// held as floats inside its region keeps its origin; switching gives the other pipeline's
    /// memory back.
    void judge(std::span<const Box<Real, Dim>> boxes, const SceneBounds<Real, Dim>& bounds) {
        if constexpr (!kMayRound) {
            precision_ = HeldPrecision::floats;
        } else {
            const std::size_t n = boxes.size();
            const bool inside = judged_ && bounds.within(judgement_.region);
            const bool stale = !inside || 4 * n > 5 * judged_boxes_ || 5 * n < 4 * judged_boxes_ ||
                               ++since_judged_ >= tuning::judge_precision_every;
            if (!stale) return;
            FloatResolution<Real, Dim> judged = judge_float_resolution(boxes, bounds);
            judged_ = true;
            judged_boxes_ = n;
            since_judged_ = 0;
            if (judged.floats && precision_ == HeldPrecision::floats && inside) return;
            judgement_ = judged;
            if (judged.floats) {
                rounded_.set_origin(judged.origin);
                exact_ = ExactPipeline();
                precision_ = HeldPrecision::floats;
            } else {
                rounded_ = RoundedPipeline();
                precision_ = HeldPrecision::doubles;
            }
        }
    }

    /// Reports every overlapping pair of `boxes` (box `slot` under ids[slot], or under `slot`
    /// where `ids` is empty) as judge() chose to hold them; `bounds` as judge() had them.
    template <class Report>
    void detect(std::span<const Box<Real, Dim>> boxes, std::span<const BoxId> ids, const SceneBounds<Real, Dim>& bounds,
                const DetectionSettings& settings, Report& report, DetectProfile& profile, bool ids_kept = false) {
        SMB_ASSERT(precision_ != HeldPrecision::none, "judge() chose what to hold");
        retested_ = 0;
        if (uses_rounded()) {
            rounded_.set_scene_bounds(bounds.lo, bounds.hi);
            rounded_.detect(boxes, ids, settings, report, profile, ids_kept);
            if constexpr (kMayRound) retested_ = rounded_.retested();
        } else {
            exact_.detect(boxes, ids, settings, report, profile, ids_kept);
        }
    }

    /// A detection of no boxes: forgets the cuts, the order and the judgement.
    template <class Report>
    void detect_nothing(const DetectionSettings& settings, Report& report, DetectProfile& profile) {
        clear();
        exact_.detect(std::span<const Box<Real, Dim>>{}, {}, settings, report, profile);
    }

    // The order's life between detections (cell_order.hpp), in both pipelines or the one in use.
    void forget_slots_from(std::size_t n) {
        exact_.forget_slots_from(n);
        rounded_.forget_slots_from(n);
    }
    void fold_removals(const SlotRenumbering& renumbering) {
        exact_.fold_removals(renumbering);
        rounded_.fold_removals(renumbering);
    }
    void follow_own_order() {
        if (uses_rounded())
            rounded_.follow_own_order();
        else
            exact_.follow_own_order();
    }
    [[nodiscard]] std::span<const Slot> order() const noexcept {
        return uses_rounded() ? rounded_.order() : exact_.order();
    }
    [[nodiscard]] std::size_t listed() const noexcept { return uses_rounded() ? rounded_.listed() : exact_.listed(); }

    /// Gives the pipelines' memory back (their cuts and order too); keeps the judgement.
    void release() {
        exact_ = ExactPipeline();
        rounded_ = RoundedPipeline();
        if constexpr (kMayRound) {
            if (precision_ == HeldPrecision::floats) rounded_.set_origin(judgement_.origin);
        }
    }

    /// Forgets everything, the judgement included.
    void clear() {
        exact_ = ExactPipeline();
        rounded_ = RoundedPipeline();
        retested_ = 0;
        judged_ = false;
        judged_boxes_ = 0;
        since_judged_ = 0;
        precision_ = HeldPrecision::none;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept { return exact_.bytes_held() + rounded_.bytes_held(); }

private:
    using ExactPipeline = PersistentCutPipeline<Real, Dim, Real>;
    using RoundedPipeline = std::conditional_t<kMayRound, PersistentCutPipeline<float, Dim, Real>, ExactPipeline>;

    [[nodiscard]] bool uses_rounded() const noexcept { return kMayRound && precision_ == HeldPrecision::floats; }

    ExactPipeline exact_;
    RoundedPipeline rounded_;
    std::size_t retested_ = 0;
    FloatResolution<Real, Dim> judgement_;
    bool judged_ = false;
    std::size_t judged_boxes_ = 0;
    std::size_t since_judged_ = 0;
    HeldPrecision precision_ = HeldPrecision::none;
};

}  // namespace smb::detail
