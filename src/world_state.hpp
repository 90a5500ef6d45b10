// SPDX-License-Identifier: MIT
#pragma once
// What a World holds: its boxes (box_store.hpp), its settings, its filters and static boxes
// (filters/world_filters.hpp), and the path its last detection took, one of:
// - the detection engine over the store (engine/detection_engine.hpp), the default: the
//   persistent cuts, or the skin list with WorldSettings::skin;
// - the paper's lists (paper/paper_pipeline.hpp), with WorldSettings::pipeline = paper_lists;
// - the filtered detection, once a filter, a static box or a predicate is in use (its state is
//   the filters' own);
// - the periodic detection (periodic/periodic_path.hpp), for detect(domain, ...).
// A detection that takes another path than the last one starts that path afresh, and the path
// left behind gives its memory back.

#include <cstddef>
#include <span>
#include <utility>
#include <variant>
#include <vector>

#include "core/box_store.hpp"
#include "core/pair_output.hpp"
#include "core/settings_check.hpp"
#include "core/stopwatch.hpp"
#include "engine/detection_engine.hpp"
#include "filters/world_filters.hpp"
#include "paper/paper_pipeline.hpp"
#include "periodic/periodic_path.hpp"
#include "smb/errors.hpp"
#include "smb/held_precision.hpp"
#include "smb/pair_events.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// The filtered detection is live; its state is the World's filters' (counted with them).
template <std::floating_point Real, int Dim>
struct FilteredPath {
    // A constructor, not an aggregate: clang before 16 cannot build an aggregate from parentheses,
    // which std::variant::emplace does.
    explicit FilteredPath(const WorldFilters<Real, Dim>* held) noexcept : filters(held) {}

    const WorldFilters<Real, Dim>* filters;

    [[nodiscard]] HeldPrecision precision() const noexcept { return filters->precision(); }
    [[nodiscard]] std::size_t retested() const noexcept { return filters->retested(); }
    [[nodiscard]] static std::size_t bytes_held() noexcept { return 0; }
};

template <std::floating_point Real, int Dim>
class WorldState {
public:
    explicit WorldState(const WorldSettings& settings)
        : settings_(validated_settings(settings)), path_(std::in_place_type<DetectionEngine<Real, Dim>>) {}
    WorldState(const WorldState&) = delete;
    WorldState& operator=(const WorldState&) = delete;

    BoxStore<Real, Dim>& store() noexcept { return store_; }
    const BoxStore<Real, Dim>& store() const noexcept { return store_; }
    const WorldSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }
    const DetectProfile& last_profile() const noexcept { return profile_; }
    WorldFilters<Real, Dim>& filters() noexcept { return filters_; }
    const WorldFilters<Real, Dim>& filters() const noexcept { return filters_; }

    HeldPrecision last_precision() const noexcept {
        return std::visit([](const auto& path) { return path.precision(); }, path_);
    }
    std::size_t last_retested_pairs() const noexcept {
        return std::visit([](const auto& path) { return path.retested(); }, path_);
    }

    /// Forgets every box and gives back every array, as a new world would have them.
    void clear() {
        store_ = BoxStore<Real, Dim>();
        filters_.clear();
        path_.template emplace<DetectionEngine<Real, Dim>>();
        std::vector<Pair>().swap(chunk_);
        stats_ = {};
        profile_ = {};
        cleared_ = true;
    }

    DetectStats detect(const PairSink& sink) {
        const Stopwatch whole;
        DetectStats stats;
        DetectProfile profile;
        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        if (filters_.wanted()) [[unlikely]] {
            // The filters compact the store on their own: the other paths' lists are forgotten.
            enter<Filtered>(&filters_);
            filters_.detect(store_, settings_, settings_.skin, output, stats, profile);
        } else if (settings_.pipeline == Pipeline::paper_lists) {
            Paper& paper = enter<Paper>(settings_);
            if (store_.has_removals()) {
                paper.fold_removals(store_.compact(paper.listed()));
                profile.update_seconds = settings_.profile ? whole.seconds() : 0;
            }
            auto report_slots = [&](Slot a, Slot b) { output(store_.id_at(a), store_.id_at(b)); };
            paper.detect(store_.boxes(), report_slots, settings_.profile, profile);
        } else {
            Engine& engine = enter<Engine>();
            if (store_.has_removals()) {
                engine.fold_removals(store_.compact(engine.listed(store_.slot_count())));
                profile.update_seconds = settings_.profile ? whole.seconds() : 0;
            }
            engine.detect({store_.boxes(), store_.ids(), nullptr, true, true}, settings_, settings_.skin, output, stats,
                          profile);
        }
        stats.boxes = store_.slot_count();
        output.flush();
        finish(stats, profile, whole);
        finish_for_events();
        return stats;
    }

    /// The periodic detection (periodic/periodic_path.hpp) into `pairs`, `events` (if not null)
    /// updated with their (a, b) first.
    DetectStats detect_periodic(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs,
                                PairEvents* events) {
        check_domain(domain);
        if (filters_.wanted())
            throw ArgumentError(
                "detect(domain, pairs): a periodic detection does not apply filters, static boxes or a predicate, "
                "and some are in use");
        const Stopwatch whole;
        Periodic& periodic = enter<Periodic>();
        // The periodic path sees box i at index i: compacting moves the last boxes into the
        // holes, which costs them their place in its order, nothing more. A box too large for the
        // domain throws as it is gathered, after the compaction: that costs speed, not results.
        if (store_.has_removals()) store_.compact(store_.slot_count());
        DetectStats stats;
        DetectProfile profile;
        if (events == nullptr) {
            stats = periodic.detect(store_.boxes(), store_.ids(), domain, settings_, pairs, profile, settings_.skin);
            finish_for_events();
        } else {
            stats = periodic.detect(
                store_.boxes(), store_.ids(), domain, settings_, pairs,
                [&](std::span<const Pair> plain) {
                    finish_for_events();
                    if (cleared_before_detect_) events->replace_all();
                    events->update(plain, reinserted_before_detect());
                },
                profile, settings_.skin);
        }
        finish(stats, profile, whole);
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
        const std::size_t path = std::visit([](const auto& live) { return live.bytes_held(); }, path_);
        return sizeof(*this) + store_.bytes_held() + path + filters_.bytes_held() + chunk_.capacity() * sizeof(Pair) +
               removed_before_detect_.capacity() * sizeof(BoxId);
    }

private:
    using Engine = DetectionEngine<Real, Dim>;
    using Paper = PaperPipeline<Real, Dim>;
    using Periodic = PeriodicPath<Real, Dim>;
    using Filtered = FilteredPath<Real, Dim>;
    using Path = std::variant<Engine, Paper, Filtered, Periodic>;

    /// The path `P`, made live (from `args`) unless it is already; the filters give back what
    /// their detection held when another path takes over.
    template <class P, class... Args>
    P& enter(Args&&... args) {
        if (P* live = std::get_if<P>(&path_)) return *live;
        if (std::holds_alternative<Filtered>(path_)) filters_.disengage();
        return path_.template emplace<P>(std::forward<Args>(args)...);
    }

    /// What every detection closes with, whichever path it took.
    void finish(DetectStats& stats, const DetectProfile& profile, const Stopwatch& whole) {
        stats.bytes_held = bytes_held();
        stats.total_seconds = whole.seconds();
        stats_ = stats;
        if (settings_.profile) profile_ = profile;
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
    DetectProfile profile_;  // all zero unless settings_.profile
    WorldFilters<Real, Dim> filters_;
    Path path_;
    std::vector<Pair> chunk_;
    std::vector<BoxId> removed_before_detect_;
    bool cleared_ = false;
    bool cleared_before_detect_ = false;
};

}  // namespace smb::detail
