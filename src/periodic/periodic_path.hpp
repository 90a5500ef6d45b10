// SPDX-License-Identifier: MIT
#pragma once
// The periodic detection a World or a Detector runs: the caller's boxes brought into the domain
// with their images (periodic_images.hpp), detected by a detection engine of their own, the pairs
// turned into the caller's pairs and shifts (periodic_report.hpp).
//
// The engine keeps its cuts and its order (and, with a skin, its candidates) from one detection to
// the next, as it does for an array: the caller's box i is gathered at index i, and its images
// after all the boxes, in box order. An image that comes or goes moves the images after it by one
// index, and a box that wraps around jumps by a period: either costs those boxes their place in
// the order and their fat boxes (speed, never exactness); images are few (the boxes within their
// extent of a domain face).

#include <concepts>
#include <cstddef>
#include <span>
#include <vector>

#include "core/collected_pairs.hpp"
#include "core/stopwatch.hpp"
#include "engine/detection_engine.hpp"
#include "periodic/periodic_images.hpp"
#include "periodic/periodic_report.hpp"
#include "smb/pair.hpp"
#include "smb/periodic.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class PeriodicPath {
public:
    /// Replaces the contents of `pairs` by the periodic pairs of `boxes`, named by `names`
    /// (empty: by index), in `domain` (checked by check_domain). All or nothing: whatever it
    /// throws (InvalidBoxError for a box the domain refuses, first), `pairs` holds what it held
    /// before and the pipeline is as it was.
    DetectStats detect(std::span<const Box<Real, Dim>> boxes, std::span<const BoxId> names,
                       const PeriodicDomain<Real, Dim>& domain, const DetectionSettings& settings,
                       std::vector<PeriodicPair>& pairs, DetectProfile& profile, double skin = 0) {
        const Stopwatch update{settings.profile};
        DetectStats stats;
        stats.boxes = boxes.size();
        images_.build(boxes, names, domain);
        profile.update_seconds = update.seconds();
        replace_on_success(pairs, [&] {
            PeriodicReport<Real, Dim> report(images_, boxes, names, domain, pairs, settings.max_pairs_held);
            engine_.detect({images_.gathered(), images_.keys(), &images_.bounds(), true}, settings, skin, report, stats,
                           profile);
            return true;
        });
        stats.pairs = pairs.size();
        return stats;
    }

    /// detect(), then update_events(the (a, b) of the pairs): all or nothing, so the pairs are
    /// collected apart and handed over once the events took them.
    template <class UpdateEvents>
    DetectStats detect(std::span<const Box<Real, Dim>> boxes, std::span<const BoxId> names,
                       const PeriodicDomain<Real, Dim>& domain, const DetectionSettings& settings,
                       std::vector<PeriodicPair>& pairs, UpdateEvents&& update_events, DetectProfile& profile,
                       double skin = 0) {
        scratch_.clear();
        const DetectStats stats = detect(boxes, names, domain, settings, scratch_, profile, skin);
        plain_.resize(scratch_.size());
        for (std::size_t i = 0; i < scratch_.size(); ++i) plain_[i] = Pair{scratch_[i].a, scratch_[i].b};
        update_events(std::span<const Pair>(plain_));
        pairs.swap(scratch_);
        return stats;
    }

    [[nodiscard]] HeldPrecision precision() const noexcept { return engine_.precision(); }
    [[nodiscard]] std::size_t retested() const noexcept { return engine_.retested(); }

    void clear() {
        images_.clear();
        engine_.clear();
        std::vector<Pair>().swap(plain_);
        std::vector<PeriodicPair>().swap(scratch_);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return images_.bytes_held() + engine_.bytes_held() + plain_.capacity() * sizeof(Pair) +
               scratch_.capacity() * sizeof(PeriodicPair);
    }

private:
    PeriodicImages<Real, Dim> images_;
    DetectionEngine<Real, Dim> engine_;
    std::vector<Pair> plain_;            // the (a, b) of the pairs, for the events
    std::vector<PeriodicPair> scratch_;  // the pairs, until the events took them
};

}  // namespace smb::detail
