// SPDX-License-Identifier: MIT
#pragma once
// DetectionEngine::detect(), the one place every front door's detection runs through. Only
// engine/detection_engine.cpp includes it: the pipeline it reaches is compiled there, once per
// box type and report (engine/engine_reports.hpp), not again in each front door's .cpp.

#include "engine/detection_engine.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
template <class Report>
void DetectionEngine<Real, Dim>::detect(const EngineInput<Real, Dim>& input, const DetectionSettings& settings,
                                        double skin, Report& report, DetectStats& stats, DetectProfile& profile) {
    const Stopwatch scan{settings.profile};
    skin_detected_ = false;
    if (input.boxes.empty()) {
        cuts_.detect_nothing(settings, report, profile);
        skin_.clear();
        return;
    }
    SceneBounds<Real, Dim> bounds;
    if (input.bounds != nullptr)
        bounds = *input.bounds;
    else if (!input.valid || HeldCutPipeline<Real, Dim>::kMayRound)
        bounds = checked_bounds(input.boxes);  // throws before any change
    cuts_.judge(input.boxes, bounds);
    profile.scan_seconds += scan.seconds();
    skin_detected_ = detected_with_skin(input, bounds, settings, skin, report, stats, profile);
    if (!skin_detected_) {
        cuts_.forget_slots_from(input.boxes.size());
        cuts_.detect(input.boxes, input.keys, bounds, settings, report, profile, input.keys_kept);
    }
}

/// With a skin, on floats (the input's own, or double input that floats resolve): the skin list
/// detects, and the cuts give their memory back when it (re)builds. When it steps aside
/// (SkinList::detect()), the cuts detect for tuning::skin_pause detections.
template <std::floating_point Real, int Dim>
template <class Report>
bool DetectionEngine<Real, Dim>::detected_with_skin(const EngineInput<Real, Dim>& input,
                                                    const SceneBounds<Real, Dim>& bounds,
                                                    const DetectionSettings& settings, double skin, Report& report,
                                                    DetectStats& stats, DetectProfile& profile) {
    if (skin == 0 || cuts_.precision() != HeldPrecision::floats) {
        skin_.clear();
        return false;
    }
    if (skin_pause_ > 0) {
        --skin_pause_;
        return false;
    }
    const bool detected = skin_.detect(input.boxes, input.keys, input.keys_kept, cuts_.origin(), bounds.lo, bounds.hi,
                                       skin, settings, report, stats, profile);
    if (!detected) {
        skin_pause_ = tuning::skin_pause;
        return false;
    }
    // A (re)build is the first skin detection after the cuts' ones.
    if (skin_.rebuilt()) cuts_.release();
    return true;
}

}  // namespace smb::detail
