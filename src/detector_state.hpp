// SPDX-License-Identifier: MIT
#pragma once
// What a Detector holds: its settings and the detection engine over the caller's array
// (engine/detection_engine.hpp), the filtered and periodic detections when they are used.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/pair_output.hpp"
#include "core/settings_check.hpp"
#include "core/stopwatch.hpp"
#include "engine/detection_engine.hpp"
#include "filters/class_detections.hpp"
#include "filters/filtered_sink.hpp"
#include "periodic/periodic_path.hpp"
#include "smb/candidate_pairs.hpp"
#include "smb/detector.hpp"
#include "smb/errors.hpp"
#include "smb/profile.hpp"
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
    const DetectProfile& last_profile() const noexcept { return profile_; }
    HeldPrecision last_precision() const noexcept {
        return classes_.split() ? classes_.precision() : engine_.precision();
    }
    std::size_t last_retested_pairs() const noexcept {
        return classes_.split() ? classes_.retested() : engine_.retested();
    }
    /// The skin's candidates after the last detection, turned into the caller's indices on the
    /// first call after it (smb/candidate_pairs.hpp).
    CandidatePairs candidates() {
        if (!skin_detected_) return {};
        if (!candidates_ready_) {
            engine_.skin_list().candidate_pairs(candidate_pairs_);
            candidate_margin_ = engine_.skin_list().candidate_margin();
            candidates_ready_ = true;
        }
        return CandidatePairs{candidate_pairs_, candidate_margin_, true};
    }
    /// Detector::suggested_order(): the engine's, where it detected over the whole array last.
    std::span<const std::uint32_t> suggested_order() const noexcept {
        return whole_array_detected_ ? engine_.suggested_order() : std::span<const std::uint32_t>();
    }
    void follow_suggested_order() {
        if (whole_array_detected_) engine_.follow_suggested_order();
    }
    void clear() {
        skin_detected_ = false;
        whole_array_detected_ = false;
        std::vector<Pair>().swap(candidate_pairs_);
        engine_.clear();
        periodic_.reset();
        classes_.clear();
        std::vector<Pair>().swap(chunk_);
        stats_ = {};
        profile_ = {};
    }

    DetectStats detect(std::span<const Box<Real, Dim>> boxes, const PairSink& sink) {
        const Stopwatch whole;
        classes_.clear();
        skin_detected_ = false;
        whole_array_detected_ = false;
        candidates_ready_ = false;
        DetectStats stats;
        DetectProfile profile;
        stats.boxes = boxes.size();
        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        engine_.detect({boxes, {}, nullptr, false}, settings_, settings_.skin, output, stats, profile);
        output.flush();
        skin_detected_ = engine_.skin_detected();
        whole_array_detected_ = true;
        return finish(stats, profile, whole);
    }

    /// The detection with filters (smb/filter.hpp), `filters` checked against `boxes`. Where the
    /// filters make two interaction classes or more, or leave boxes out of their one class, each
    /// class is detected apart as a World's are (filters/class_detections.hpp), and no candidates
    /// are offered (the skin's would name the boxes gathered). Otherwise the caller's array is
    /// detected as it is, through the filtered sink (filters/filtered_sink.hpp).
    DetectStats detect_filtered(std::span<const Box<Real, Dim>> boxes, const DetectFilters& filters,
                                const PairSink& sink) {
        if (!filters_in_use(filters)) return detect(boxes, sink);
        if (!filters.filters.empty()) {
            const Stopwatch whole;
            // The boxes are checked first, so that an invalid one is named by its index in the
            // caller's array.
            (void)checked_bounds(boxes);
            classes_.follow(filters.filters);
            if (classes_.classes().count() != 1 || classes_.placed() < boxes.size())
                return detect_by_classes(boxes, filters, sink, whole);
        }
        FilteredSink filtered(filters, sink, settings_.pair_chunk_size);
        detect(boxes, PairSink(std::ref(filtered)));
        stats_.boxes = boxes.size();
        stats_.pairs = filtered.finish();
        return stats_;
    }

    /// The periodic detection (periodic/periodic_path.hpp) into `pairs`, `update_events` (if
    /// any) given the (a, b) of the pairs first. Its path is made on the first periodic call, so
    /// that a detector that never uses one stays small. No candidates are offered after it.
    template <class... UpdateEvents>
    DetectStats detect_periodic(std::span<const Box<Real, Dim>> boxes, const PeriodicDomain<Real, Dim>& domain,
                                std::vector<PeriodicPair>& pairs, UpdateEvents&&... update_events) {
        check_domain(domain);  // the boxes are checked as they are gathered
        skin_detected_ = false;
        whole_array_detected_ = false;
        if (!periodic_) periodic_ = std::make_unique<PeriodicPath<Real, Dim>>();
        const Stopwatch whole;
        DetectProfile profile;
        return finish(periodic_->detect(boxes, {}, domain, settings_, pairs, update_events..., profile, settings_.skin),
                      profile, whole);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return sizeof(*this) + engine_.bytes_held() + (chunk_.capacity() + candidate_pairs_.capacity()) * sizeof(Pair) +
               classes_.bytes_held() + (periodic_ ? sizeof(PeriodicPath<Real, Dim>) + periodic_->bytes_held() : 0);
    }

private:
    /// The filtered detection class by class, the classes following `filters` already.
    DetectStats detect_by_classes(std::span<const Box<Real, Dim>> boxes, const DetectFilters& filters,
                                  const PairSink& sink, const Stopwatch& whole) {
        engine_.clear();
        skin_detected_ = false;
        whole_array_detected_ = false;
        DetectStats stats;
        DetectProfile profile;
        stats.boxes = boxes.size();
        const std::span<const Filter> filter = filters.filters;
        classes_.gather([&](std::size_t i) { return boxes[i]; }, [&](std::size_t i) { return IdFilter{i, filter[i]}; });
        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        const PairRules rules{filters.statics, filters.predicate ? &filters.predicate : nullptr};
        classes_.detect(settings_, settings_.skin, output, rules, stats, profile);
        output.flush();
        return finish(stats, profile, whole);
    }

    /// What every detection closes with, whichever path it took.
    DetectStats finish(DetectStats stats, const DetectProfile& profile, const Stopwatch& whole) {
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        if (settings_.profile) profile_ = profile;
        return stats;
    }

    DetectorSettings settings_;
    DetectionEngine<Real, Dim> engine_;
    DetectStats stats_;
    DetectProfile profile_;  // all zero unless settings_.profile
    std::vector<Pair> chunk_;
    ClassDetections<Real, Dim> classes_{1};
    bool skin_detected_ = false;         // the last detection ran on the skin list, and returned
    bool whole_array_detected_ = false;  // the engine's order is of the last detection's array
    bool candidates_ready_ = false;      // candidate_pairs_ and candidate_margin_ are its own
    std::vector<Pair> candidate_pairs_;
    double candidate_margin_ = 0;
    std::unique_ptr<PeriodicPath<Real, Dim>> periodic_;
};

}  // namespace smb::detail
