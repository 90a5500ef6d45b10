// SPDX-License-Identifier: MIT
#pragma once
// What a Detector holds: its settings, the persistent-cut pipeline over the caller's array,
// holding floats or a copy of the doubles (held_cut_pipeline.hpp), and the skin list.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "core/pair_output.hpp"
#include "core/scene_bounds.hpp"
#include "core/settings_check.hpp"
#include "core/stopwatch.hpp"
#include "cuts/held_cut_pipeline.hpp"
#include "filters/detector_classes.hpp"
#include "periodic/periodic_path.hpp"
#include "skin/skin_list.hpp"
#include "smb/candidate_pairs.hpp"
#include "smb/detector.hpp"
#include "smb/errors.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class DetectorState {
public:
    explicit DetectorState(const DetectorSettings& settings) : settings_(validated_settings(settings)) {}
    DetectorState(const DetectorState&) = delete;
    DetectorState& operator=(const DetectorState&) = delete;

    const DetectorSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }
    HeldPrecision last_precision() const noexcept {
        return classes_.split() ? classes_.precision() : pipeline_.precision();
    }
    std::size_t last_retested_pairs() const noexcept { return classes_.split() ? classes_.retested() : retested_; }
    /// A filtered detection reported fewer pairs than it found, maybe over fewer boxes than the
    /// caller's (filters/filtered_sink.hpp).
    void set_reported(std::size_t boxes, std::size_t pairs) noexcept {
        stats_.boxes = boxes;
        stats_.pairs = pairs;
    }
    /// Where a filtered detection gathers the boxes that can pair, and their indices.
    std::vector<Box<Real, Dim>>& gathered() noexcept { return gathered_; }
    std::vector<std::uint32_t>& gathered_origin() noexcept { return gathered_origin_; }
    /// A filtered detection split by interaction classes (filters/detector_classes.hpp).
    DetectorClasses<Real, Dim>& classes() noexcept { return classes_; }
    /// The detection was split: the pipeline over the whole array gives its memory back.
    void release_whole_pipeline() {
        pipeline_.clear();
        skin_.clear();
        retested_ = 0;
    }
    /// The periodic detection (periodic/periodic_path.hpp), made on the first periodic call so
    /// that a detector that never uses one stays small.
    PeriodicPath<Real, Dim>& periodic() {
        if (!periodic_) periodic_ = std::make_unique<PeriodicPath<Real, Dim>>();
        return *periodic_;
    }
    void set_last_stats(const DetectStats& stats) noexcept { stats_ = stats; }

    /// The skin's candidates after the last detection, turned into the caller's indices on the
    /// first call after it (smb/candidate_pairs.hpp).
    CandidatePairs candidates() {
        if (!skin_detected_) return {};
        if (!candidates_ready_) {
            skin_.candidate_pairs(candidate_pairs_);
            candidate_margin_ = skin_.candidate_margin();
            candidates_ready_ = true;
        }
        return CandidatePairs{candidate_pairs_, candidate_margin_, true};
    }
    /// A filtered detection ran over the boxes it gathered: the candidates name those, not the
    /// caller's indices.
    void forget_candidates() noexcept { skin_detected_ = false; }

    void clear() {
        forget_candidates();
        std::vector<Pair>().swap(candidate_pairs_);
        pipeline_.clear();
        skin_.clear();
        periodic_.reset();
        skin_pause_ = 0;
        retested_ = 0;
        std::vector<Box<Real, Dim>>().swap(gathered_);
        std::vector<std::uint32_t>().swap(gathered_origin_);
        classes_.clear();
        std::vector<Pair>().swap(chunk_);
        stats_ = {};
    }

    DetectStats detect(std::span<const Box<Real, Dim>> boxes, const PairSink& sink) {
        const Stopwatch whole;
        classes_.clear();
        forget_candidates();
        candidates_ready_ = false;
        DetectStats stats;
        stats.boxes = boxes.size();
        SceneBounds<Real, Dim> bounds;
        if (!boxes.empty()) {
            bounds = checked_bounds(boxes);  // throws before any change
            pipeline_.judge(boxes, bounds);
        }
        stats.scan_seconds = whole.seconds();

        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        retested_ = 0;
        bool used_skin = false;
        if (boxes.empty()) {
            pipeline_.detect_nothing(settings_, output, stats);
            skin_.clear();
        } else if (used_skin = detected_with_skin(boxes, bounds, output, stats); !used_skin) {
            pipeline_.forget_slots_from(boxes.size());
            pipeline_.detect(boxes, {}, bounds, settings_, output, stats);
            retested_ = pipeline_.retested();
        }
        output.flush();
        skin_detected_ = used_skin;
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        return stats;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return sizeof(*this) + pipeline_.bytes_held() + skin_.bytes_held() +
               (chunk_.capacity() + candidate_pairs_.capacity()) * sizeof(Pair) +
               gathered_.capacity() * sizeof(Box<Real, Dim>) + gathered_origin_.capacity() * sizeof(std::uint32_t) +
               classes_.bytes_held() + (periodic_ ? sizeof(PeriodicPath<Real, Dim>) + periodic_->bytes_held() : 0);
    }

private:
    /// With a skin, on floats (the input's own, or double input that floats resolve): the skin
    /// list detects, and the pipelines give their memory back when it (re)builds. When it steps
    /// aside (SkinList::detect()), the pipelines detect for kSkinPause detections.
    bool detected_with_skin(std::span<const Box<Real, Dim>> boxes, const SceneBounds<Real, Dim>& bounds,
                            PairOutput& output, DetectStats& stats) {
        if (settings_.skin == 0 || pipeline_.precision() != HeldPrecision::floats) {
            skin_.clear();
            return false;
        }
        if (skin_pause_ > 0) {
            --skin_pause_;
            return false;
        }
        if (!skin_.detect(boxes, pipeline_.origin(), bounds.lo, bounds.hi, settings_.skin, settings_, output, stats)) {
            skin_pause_ = kSkinPause;
            return false;
        }
        retested_ = skin_.retested();
        // A (re)build is the first skin detection after the pipeline's ones.
        if (stats.skin_rebuilt) pipeline_.release();
        return true;
    }

    static constexpr std::size_t kSkinPause = 64;

    DetectorSettings settings_;
    HeldCutPipeline<Real, Dim> pipeline_;
    SkinList<Real, Dim> skin_;
    std::size_t skin_pause_ = 0;
    std::size_t retested_ = 0;
    DetectStats stats_;
    std::vector<Pair> chunk_;
    std::vector<Box<Real, Dim>> gathered_;
    std::vector<std::uint32_t> gathered_origin_;
    DetectorClasses<Real, Dim> classes_;
    bool skin_detected_ = false;     // the last detection ran on the skin list, and returned
    bool candidates_ready_ = false;  // candidate_pairs_ and candidate_margin_ are its own
    std::vector<Pair> candidate_pairs_;
    double candidate_margin_ = 0;
    std::unique_ptr<PeriodicPath<Real, Dim>> periodic_;
};

}  // namespace smb::detail
