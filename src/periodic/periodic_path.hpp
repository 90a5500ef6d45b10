// SPDX-License-Identifier: MIT
#pragma once
// The periodic detection a World or a Detector runs: the caller's boxes brought into the domain
// with their images (periodic_images.hpp), detected by a persistent-cut pipeline of their own
// (held_cut_pipeline.hpp: floats for double boxes where floats resolve the scene, threads as
// the settings say), the pairs turned into the caller's pairs and shifts (periodic_report.hpp).
//
// The pipeline keeps its cuts and its order from one detection to the next, as it does for an
// array: the caller's box i is gathered at index i, and its images after all the boxes, in box
// order. An image that comes or goes moves the images after it by one index, which costs those
// boxes their place in the order (speed, never exactness); images are few (the boxes within
// their extent of a domain face).
//
// With a skin (a Detector's DetectorSettings::skin), the skin list (skin/skin_list.hpp) keeps
// the candidate pairs of the gathered array as it does for an ordinary array, on the same terms:
// only where the pipeline holds floats, stepping aside for a while when the skin does not pay.
// A box that wraps around (its canonical box jumps by a period) or an image that moves to
// another index leaves its fat box there, and finds its candidates again.

#include <concepts>
#include <cstddef>
#include <span>
#include <vector>

#include "core/scene_bounds.hpp"
#include "core/stopwatch.hpp"
#include "cuts/held_cut_pipeline.hpp"
#include "periodic/periodic_images.hpp"
#include "periodic/periodic_report.hpp"
#include "skin/skin_list.hpp"
#include "smb/pair.hpp"
#include "smb/periodic.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class PeriodicPath {
public:
    using box_type = Box<Real, Dim>;

    /// Replaces the contents of `pairs` by the periodic pairs of `boxes`, named by `names`
    /// (empty: by index), in `domain` (checked by check_domain). All or nothing: whatever it
    /// throws (InvalidBoxError for a box the domain refuses, first), `pairs` holds what it held
    /// before and the pipeline is as it was.
    DetectStats detect(std::span<const box_type> boxes, std::span<const BoxId> names,
                       const PeriodicDomain<Real, Dim>& domain, const DetectionSettings& settings,
                       std::vector<PeriodicPair>& pairs, double skin = 0) {
        const Stopwatch whole;
        DetectStats stats;
        stats.boxes = boxes.size();
        const Stopwatch update;
        images_.build(boxes, names, domain);
        stats.update_seconds = update.seconds();
        const std::size_t kept = pairs.size();
        const std::size_t capacity = pairs.capacity();
        try {
            PeriodicReport<Real, Dim> report(images_, boxes, names, domain, pairs, settings.max_pairs_held);
            const std::span<const box_type> gathered = images_.gathered();
            if (gathered.empty()) {
                pipeline_.detect_nothing(settings, report, stats);
            } else {
                const Stopwatch scan;
                const SceneBounds<Real, Dim>& bounds = images_.bounds();
                pipeline_.judge(gathered, bounds);
                stats.scan_seconds = scan.seconds();
                if (!detected_with_skin(gathered, bounds, skin, settings, report, stats)) {
                    pipeline_.forget_slots_from(gathered.size());
                    pipeline_.detect(gathered, images_.keys(), bounds, settings, report, stats);
                }
            }
            pairs.erase(pairs.begin(), pairs.begin() + static_cast<std::ptrdiff_t>(kept));
        } catch (...) {
            pairs.resize(kept);
            if (pairs.capacity() > capacity) pairs.shrink_to_fit();
            throw;
        }
        stats.pairs = pairs.size();
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        return stats;
    }

    /// detect(), then update_events(the (a, b) of the pairs): all or nothing, so the pairs are
    /// collected apart and handed over once the events took them.
    template <class UpdateEvents>
    DetectStats detect(std::span<const box_type> boxes, std::span<const BoxId> names,
                       const PeriodicDomain<Real, Dim>& domain, const DetectionSettings& settings,
                       std::vector<PeriodicPair>& pairs, UpdateEvents&& update_events, double skin = 0) {
        scratch_.clear();
        const DetectStats stats = detect(boxes, names, domain, settings, scratch_, skin);
        plain_.resize(scratch_.size());
        for (std::size_t i = 0; i < scratch_.size(); ++i) plain_[i] = Pair{scratch_[i].a, scratch_[i].b};
        update_events(std::span<const Pair>(plain_));
        pairs.swap(scratch_);
        return stats;
    }

    [[nodiscard]] HeldPrecision precision() const noexcept { return pipeline_.precision(); }
    [[nodiscard]] std::size_t retested() const noexcept { return pipeline_.retested(); }
    /// Images in the last detection.
    [[nodiscard]] std::size_t images() const noexcept { return images_.images(); }

    void clear() {
        images_.clear();
        pipeline_.clear();
        skin_.clear();
        skin_pause_ = 0;
        std::vector<Pair>().swap(plain_);
        std::vector<PeriodicPair>().swap(scratch_);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return images_.bytes_held() + pipeline_.bytes_held() + skin_.bytes_held() + plain_.capacity() * sizeof(Pair) +
               scratch_.capacity() * sizeof(PeriodicPair);
    }

private:
    /// The skin list's pairs are of indices into the gathered array: the report takes keys.
    template <class Report>
    struct KeyedReport {
        Report& report;
        std::span<const BoxId> keys;

        void operator()(BoxId a, BoxId b) { report(keys[a], keys[b]); }
        void append(std::span<const Pair> pairs) {
            for (const Pair& p : pairs) report(keys[p.a], keys[p.b]);
        }
    };

    /// As DetectorState's: the skin list detects where the pipeline holds floats, and steps
    /// aside for kSkinPause detections when it says it does not pay.
    template <class Report>
    bool detected_with_skin(std::span<const box_type> gathered, const SceneBounds<Real, Dim>& bounds, double skin,
                            const DetectionSettings& settings, Report& report, DetectStats& stats) {
        if (skin == 0 || pipeline_.precision() != HeldPrecision::floats) {
            skin_.clear();
            return false;
        }
        if (skin_pause_ > 0) {
            --skin_pause_;
            return false;
        }
        KeyedReport<Report> keyed{report, images_.keys()};
        if (!skin_.detect(gathered, pipeline_.origin(), bounds.lo, bounds.hi, skin, settings, keyed, stats)) {
            skin_pause_ = kSkinPause;
            return false;
        }
        if (stats.skin_rebuilt) pipeline_.release();
        return true;
    }

    static constexpr std::size_t kSkinPause = 64;

    PeriodicImages<Real, Dim> images_;
    HeldCutPipeline<Real, Dim> pipeline_;
    SkinList<Real, Dim> skin_;
    std::size_t skin_pause_ = 0;
    std::vector<Pair> plain_;            // the (a, b) of the pairs, for the events
    std::vector<PeriodicPair> scratch_;  // the pairs, until the events took them
};

}  // namespace smb::detail
