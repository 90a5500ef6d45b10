// SPDX-License-Identifier: MIT
// DetectionEngine::detect(), the one place every front door's detection runs through, compiled
// here for one box type: src/CMakeLists.txt builds this file once per type of
// instantiations.hpp (defining SMB_ENGINE_REAL and SMB_ENGINE_DIM), so that the four compile side
// by side, once per report below, and World and Detector share them instead of each compiling
// the pipeline.

#include "engine/detection_engine.hpp"
#include "core/pair_output.hpp"
#include "filters/filtered_report.hpp"
#include "periodic/periodic_report.hpp"

#if !defined(SMB_ENGINE_REAL) || !defined(SMB_ENGINE_DIM)
#error "detection_engine.cpp is compiled through the per-type files src/CMakeLists.txt writes"
#endif

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

template class DetectionEngine<SMB_ENGINE_REAL, SMB_ENGINE_DIM>;

// The reports the front doors hand the engine: the caller's chunks of pairs (a World's and a
// Detector's own detections), a filtered class by packed keys or by index, and a periodic
// domain's images. A report missing here is a link error naming DetectionEngine::detect. The
// report is the macro's variadic tail: its template arguments hold commas.
#define SMB_INSTANTIATE_DETECT(...)                                                                          \
    template void DetectionEngine<SMB_ENGINE_REAL, SMB_ENGINE_DIM>::detect<__VA_ARGS__>(                     \
        const EngineInput<SMB_ENGINE_REAL, SMB_ENGINE_DIM>&, const DetectionSettings&, double, __VA_ARGS__&, \
        DetectStats&, DetectProfile&);
SMB_INSTANTIATE_DETECT(PairOutput)
SMB_INSTANTIATE_DETECT(PackedFilterReport<PairOutput>)
SMB_INSTANTIATE_DETECT(FilteredReport<PairOutput>)
SMB_INSTANTIATE_DETECT(PeriodicReport<SMB_ENGINE_REAL, SMB_ENGINE_DIM>)
#undef SMB_INSTANTIATE_DETECT

}  // namespace smb::detail
