// SPDX-License-Identifier: MIT
#pragma once
// What a World holds: its boxes (box_store.hpp), its settings, and the pipeline that finds the
// overlapping pairs, chosen by WorldSettings::pipeline: the persistent cuts, holding floats of
// double boxes where floats resolve the scene (held_cut_pipeline.hpp), or the paper's lists.
// The pairs are handed to the caller's sink in chunks from here, whichever pipeline found them.
// Filters and static boxes (filters/world_filters.hpp) take their own path, chosen by one branch
// per detection, so that a world without them runs the default detection as it is.

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/box_store.hpp"
#include "core/pair_output.hpp"
#include "core/scene_bounds.hpp"
#include "core/settings_check.hpp"
#include "core/stopwatch.hpp"
#include "cuts/held_cut_pipeline.hpp"
#include "filters/world_filters.hpp"
#include "paper/paper_pipeline.hpp"
#include "periodic/periodic_path.hpp"
#include "smb/errors.hpp"
#include "smb/held_precision.hpp"
#include "smb/pair_events.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"
#include "smb/world.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class WorldState {
public:
    explicit WorldState(const WorldSettings& settings) : settings_(validated_settings(settings)) {}
    WorldState(const WorldState&) = delete;
    WorldState& operator=(const WorldState&) = delete;

    BoxStore<Real, Dim>& store() noexcept { return store_; }
    const BoxStore<Real, Dim>& store() const noexcept { return store_; }
    const WorldSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }
    WorldFilters<Real, Dim>& filters() noexcept { return filters_; }
    const WorldFilters<Real, Dim>& filters() const noexcept { return filters_; }
    HeldPrecision last_precision() const noexcept {
        if (periodic_engaged_) return periodic_.precision();
        if (filters_.engaged()) return filters_.precision();
        if (settings_.pipeline == Pipeline::persistent_cuts) return persistent_.precision();
        if (stats_.boxes == 0) return HeldPrecision::none;
        return std::is_same_v<Real, float> ? HeldPrecision::floats : HeldPrecision::doubles;
    }
    std::size_t last_retested_pairs() const noexcept {
        if (periodic_engaged_) return periodic_.retested();
        if (filters_.engaged()) return filters_.retested();
        return settings_.pipeline == Pipeline::persistent_cuts ? persistent_.retested() : 0;
    }

    /// Forgets every box and gives back every array, as a new world would have them.
    void clear() {
        store_ = BoxStore<Real, Dim>();
        persistent_.clear();
        paper_ = PaperPipeline<Real, Dim>(&store_, &settings_);
        filters_.clear();
        periodic_.clear();
        periodic_engaged_ = false;
        std::vector<Pair>().swap(chunk_);
        stats_ = {};
        cleared_ = true;
    }

    DetectStats detect(const PairSink& sink) {
        leave_periodic();
        if (filters_.wanted() || filters_.engaged()) [[unlikely]] {
            if (filters_.wanted()) return detect_filtered(sink);
            filters_.disengage();  // the default pipelines were reset when it engaged
        }
        const Stopwatch whole;
        DetectStats stats;
        if (store_.has_removals()) {
            const bool paper = settings_.pipeline == Pipeline::paper_lists;
            const SlotRenumbering renumbering = store_.compact(paper ? paper_.listed() : persistent_.listed());
            if (paper)
                paper_.fold_removals(renumbering);
            else
                persistent_.fold_removals(renumbering);
            stats.update_seconds = whole.seconds();
        }
        stats.boxes = store_.slot_count();

        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        if (settings_.pipeline == Pipeline::paper_lists) {
            auto report_slots = [&](Slot a, Slot b) { output(store_.id_at(a), store_.id_at(b)); };
            paper_.detect(report_slots, stats);
        } else if (store_.slot_count() == 0) {
            persistent_.detect_nothing(settings_, output, stats);
        } else {
            // The store holds valid boxes only: this pass finds the bounds and throws nothing.
            // Float boxes are held as they are, and need no bounds.
            const Stopwatch scan;
            SceneBounds<Real, Dim> bounds;
            if constexpr (HeldCutPipeline<Real, Dim>::kMayRound) bounds = checked_bounds(store_.boxes());
            persistent_.judge(store_.boxes(), bounds);
            stats.scan_seconds = scan.seconds();
            persistent_.detect(store_.boxes(), store_.ids(), bounds, settings_, output, stats);
        }
        output.flush();
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        finish_for_events();
        return stats;
    }

    /// The periodic detection (periodic/periodic_path.hpp) into `pairs`, and `events` (if not
    /// null) updated with the (a, b) of the pairs before they replace the contents of `pairs`.
    /// The default pipelines forget their lists when it takes over, as for the filtered path.
    DetectStats detect_periodic(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs,
                                PairEvents* events) {
        check_domain(domain);
        if (filters_.wanted())
            throw ArgumentError(
                "detect(domain, pairs): a periodic detection does not apply filters, static boxes or a predicate, "
                "and some are in use");
        const Stopwatch whole;
        if (filters_.engaged()) filters_.disengage();
        if (!periodic_engaged_) {
            persistent_.clear();
            paper_ = PaperPipeline<Real, Dim>(&store_, &settings_);
            periodic_engaged_ = true;
        }
        // The periodic pipeline sees box i at index i: compacting moves the last boxes into the
        // holes, which costs them their place in its order, nothing more. The boxes are checked
        // as they are gathered: a box too large for the domain throws then, and what changed
        // before (the compaction, the default pipelines forgotten) costs speed, not results.
        if (store_.has_removals()) store_.compact(store_.slot_count());
        DetectStats stats;
        if (events == nullptr) {
            stats = periodic_.detect(store_.boxes(), store_.ids(), domain, settings_, pairs);
            finish_for_events();
        } else {
            stats = periodic_.detect(store_.boxes(), store_.ids(), domain, settings_, pairs,
                                     [&](std::span<const Pair> plain) {
                                         finish_for_events();
                                         if (cleared_before_detect_) events->replace_all();
                                         events->update(plain, reinserted_before_detect());
                                     });
        }
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        return stats;
    }

    /// Ids removed between the detection before and the last one, and inserted again: new boxes
    /// under old ids, for PairEvents. Empty (and no allocation) in the common case.
    [[nodiscard]] std::vector<BoxId> reinserted_before_detect() const {
        std::vector<BoxId> ids;
        for (const BoxId id : removed_before_detect_) {
            if (store_.contains(id)) ids.push_back(id);
        }
        return ids;
    }
    /// Whether clear() was called between the detection before and the last one.
    [[nodiscard]] bool cleared_before_detect() const noexcept { return cleared_before_detect_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        // World allocates this state itself, so its own size counts too.
        return sizeof(*this) + store_.bytes_held() + persistent_.bytes_held() + paper_.bytes_held() +
               filters_.bytes_held() + periodic_.bytes_held() + chunk_.capacity() * sizeof(Pair) +
               removed_before_detect_.capacity() * sizeof(BoxId);
    }

private:
    /// The detection with filters or statics in use (world_filters.hpp). It compacts the store
    /// on its own, so the default pipelines forget their lists when it takes over.
    DetectStats detect_filtered(const PairSink& sink) {
        leave_periodic();
        const Stopwatch whole;
        DetectStats stats;
        if (!filters_.engaged()) {
            persistent_.clear();
            paper_ = PaperPipeline<Real, Dim>(&store_, &settings_);
        }
        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        filters_.detect(store_, settings_, output, stats);
        output.flush();
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        finish_for_events();
        return stats;
    }

    /// After periodic detections, an ordinary one starts its pipelines afresh (they were
    /// cleared when the periodic path took over) and the periodic path gives its memory back.
    void leave_periodic() {
        if (!periodic_engaged_) return;
        periodic_.clear();
        periodic_engaged_ = false;
    }

    /// For pair events, after a detection that completed: what was removed, or cleared, between
    /// the detection before and this one, whichever path detected.
    void finish_for_events() {
        store_.take_removed_log(removed_before_detect_);
        cleared_before_detect_ = std::exchange(cleared_, false);
    }

    WorldSettings settings_;
    BoxStore<Real, Dim> store_;
    DetectStats stats_;
    HeldCutPipeline<Real, Dim> persistent_;
    PaperPipeline<Real, Dim> paper_{&store_, &settings_};
    WorldFilters<Real, Dim> filters_;
    PeriodicPath<Real, Dim> periodic_;
    bool periodic_engaged_ = false;
    std::vector<Pair> chunk_;
    std::vector<BoxId> removed_before_detect_;
    bool cleared_ = false;
    bool cleared_before_detect_ = false;
};

}  // namespace smb::detail
