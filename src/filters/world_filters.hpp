// SPDX-License-Identifier: MIT
#pragma once
// A World's filters and static boxes, and the detection it runs once any is in use (the
// default detection in world_state.hpp stays as it is, one branch away). Per slot of the store:
// the filter words, the static flag and the position in the list of moving boxes. The moving
// boxes that can pair with something (not static, category and mask not 0) are gathered in the
// order of that list and detected by their own engine, or class by class (class_detections.hpp).
// The statics stay out of it: each moving box meets them through its cache (static_contacts.hpp)
// over a grid of the statics, built again only when the statics change.
//
// The list of moving boxes keeps each box at its position from one detection to the next (a box
// that leaves it is swap-removed, a box that joins it is appended), so the pipeline sees the
// same box at the same index and keeps its speed; a position that changes box costs speed there,
// never exactness.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/box_store.hpp"
#include "core/pair_output.hpp"
#include "core/slot_renumbering.hpp"
#include "core/stopwatch.hpp"
#include "core/tuning.hpp"
#include "engine/detection_engine.hpp"
#include "filters/class_detections.hpp"
#include "filters/filtered_report.hpp"
#include "filters/static_contacts.hpp"
#include "filters/static_grid.hpp"
#include "smb/filter.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class WorldFilters {
public:
    /// Whether the next detection needs this path: a filter other than the default, a static
    /// box or a predicate.
    [[nodiscard]] bool wanted() const noexcept { return statics_ != 0 || non_default_ != 0 || predicate_; }

    [[nodiscard]] Filter filter_at(Slot slot) const noexcept {
        return slot < filters_.size() ? filters_[slot] : Filter{};
    }
    [[nodiscard]] bool static_at(Slot slot) const noexcept {
        return slot < statics_flag_.size() && statics_flag_[slot];
    }
    [[nodiscard]] HeldPrecision precision() const noexcept {
        return classes_.split() ? classes_.precision() : moving_boxes_.engine.precision();
    }
    [[nodiscard]] std::size_t retested() const noexcept {
        return classes_.split() ? classes_.retested() : moving_boxes_.engine.retested();
    }

    void set_filter(Slot slot, const Filter& filter, std::size_t slot_count) {
        if (slot >= filters_.size() && filter == Filter{}) return;  // the default already
        grow(slot_count);
        Filter& held = filters_[slot];
        if (held == filter) return;
        non_default_ += (filter != Filter{} ? 1 : 0) - (held != Filter{} ? 1 : 0);
        held = filter;
        if (statics_flag_[slot]) statics_changed_ = true;
        if (filter_interacts(filter) && !classes_.classes().knows(filter)) classes_stale_ = true;
        pending_.push_back(slot);
    }

    void set_static(Slot slot, bool is_static, std::size_t slot_count) {
        if (slot >= statics_flag_.size() && !is_static) return;  // dynamic already
        grow(slot_count);
        if ((statics_flag_[slot] != 0) == is_static) return;
        statics_flag_[slot] = is_static ? 1 : 0;
        statics_ = is_static ? statics_ + 1 : statics_ - 1;
        statics_changed_ = true;
        pending_.push_back(slot);
    }

    void set_predicate(PairPredicate predicate) { predicate_ = std::move(predicate); }

    /// After BoxStore::update(): a static that moved makes the grid and the caches stale.
    void note_updated(const BoxStore<Real, Dim>& store, std::span<const BoxId> ids) {
        if (statics_ == 0 || statics_changed_) return;
        for (const BoxId id : ids) {
            if (static_at(store.slot_of(id))) {
                statics_changed_ = true;
                return;
            }
        }
    }

    /// Before BoxStore::assign(boxes): a static whose box changes makes the grid stale. Statics
    /// that assign() removes are found by the next compaction.
    void note_assign(const BoxStore<Real, Dim>& store, std::span<const Box<Real, Dim>> boxes) {
        if (statics_ == 0 || statics_changed_) return;
        const std::size_t n = std::min(statics_flag_.size(), store.slot_count());
        for (std::size_t s = 0; s < n; ++s) {
            if (statics_flag_[s] == 0 || !store.alive(static_cast<Slot>(s))) continue;
            const BoxId id = store.id_at(static_cast<Slot>(s));
            if (id < boxes.size() && !(boxes[id] == store.box_at(static_cast<Slot>(s)))) {
                statics_changed_ = true;
                return;
            }
        }
    }

    /// Gives back everything the filtered detection held; the filters, statics and predicate
    /// are kept (a detection that finds none in use calls it and runs the default path).
    void disengage() {
        moving_boxes_ = {};
        grid_.clear();
        contacts_.clear();
        classes_.clear();
        classes_stale_ = true;
        std::vector<Slot>().swap(moving_);
        std::vector<Slot>().swap(position_);
        known_ = 0;
        engaged_ = false;
        statics_changed_ = true;
        if (!wanted()) {
            std::vector<Filter>().swap(filters_);
            std::vector<std::uint8_t>().swap(statics_flag_);
            std::vector<Slot>().swap(pending_);
        }
    }

    void clear() { *this = WorldFilters(); }

    /// The filtered detection: compacts the store (the caller's pipelines were told to forget
    /// it when this path engaged), then reports every pair that passes; `skin` as the engine's.
    void detect(BoxStore<Real, Dim>& store, const DetectionSettings& settings, double skin, PairOutput& output,
                DetectStats& stats, DetectProfile& profile) {
        const Stopwatch update{settings.profile};
        if (!engaged_) {
            engaged_ = true;
            known_ = 0;  // every slot is new to this path
            statics_changed_ = true;
            // Slots noted before the default path last compacted the store may name other boxes,
            // or none; every slot is visited below anyway.
            pending_.clear();
        }
        grow(store.slot_count());
        for (std::size_t s = known_; s < store.slot_count(); ++s) pending_.push_back(static_cast<Slot>(s));
        for (const Slot s : pending_) refresh_moving(s, store.alive(s));
        pending_.clear();
        if (store.has_removals()) {
            const SlotRenumbering renumbering = store.compact(known_);
            follow_compaction(renumbering, store.slot_count());
        }
        known_ = store.slot_count();
        grow(known_);
        const bool statics_rebuilt = statics_changed_;
        if (statics_changed_) rebuild_statics(store);
        if (classes_stale_ || (classes_.classes().overflowed() && ++since_classes_ >= tuning::filter_classes_every))
            rebuild_classes();
        gather(store);
        profile.update_seconds = update.seconds();
        stats.boxes = store.slot_count();

        const PairRules rules{{}, predicate_ ? &predicate_ : nullptr};
        if (classes_.split())
            classes_.detect(settings, skin, output, rules, stats, profile);
        else
            moving_boxes_.detect(settings, skin, output, rules, stats, profile);
        contacts_.detect(moving_boxes_.boxes, moving_boxes_.info, grid_, rules, output);
        stats.statics_rebuilt = statics_rebuilt;
        stats.static_refreshed = contacts_.refreshed();
        stats.static_contacts = contacts_.cached();
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return filters_.capacity() * sizeof(Filter) + statics_flag_.capacity() +
               (pending_.capacity() + moving_.capacity() + position_.capacity()) * sizeof(Slot) +
               moving_boxes_.bytes_held() + grid_.bytes_held() + contacts_.bytes_held() + classes_.bytes_held();
    }

private:
    static constexpr Slot kNowhere = kNoSlot;

    void rebuild_classes() {
        classes_.build(moving_.size(), [&](std::size_t i) { return filters_[moving_[i]]; });
        classes_stale_ = false;
        since_classes_ = 0;
        if (classes_.split()) moving_boxes_.engine.clear();
    }

    void grow(std::size_t slot_count) {
        if (filters_.size() < slot_count) filters_.resize(slot_count);
        if (statics_flag_.size() < slot_count) statics_flag_.resize(slot_count, 0);
        if (position_.size() < slot_count) position_.resize(slot_count, kNowhere);
    }

    [[nodiscard]] bool moves(Slot s) const noexcept { return statics_flag_[s] == 0 && filter_interacts(filters_[s]); }

    /// Puts slot s in the list of moving boxes or takes it out, as its flags say now; a box that
    /// stays asks the grid again (its filter may have changed).
    void refresh_moving(Slot s, bool alive) {
        const bool in = position_[s] != kNowhere;
        const bool wanted = alive && moves(s);
        // A value the classes do not know: the rebuild gives every box its class.
        if (wanted && !classes_.classes().knows(filters_[s])) classes_stale_ = true;
        if (wanted && !in) {
            position_[s] = static_cast<Slot>(moving_.size());
            moving_.push_back(s);
            classes_.place(position_[s], filters_[s]);
            contacts_.push_back();
        } else if (!wanted && in) {
            remove_position(position_[s]);
        } else if (wanted) {
            contacts_.invalidate(position_[s]);
            classes_.place(position_[s], filters_[s]);
        }
    }

    /// Swap-removes position p of the list. `forget_slot` false: its slot was removed from the
    /// store, and its number may already be another box's.
    void remove_position(Slot p, bool forget_slot = true) {
        if (forget_slot) position_[moving_[p]] = kNowhere;
        const Slot last = moving_.back();
        classes_.swap_remove(p, moving_.size() - 1);
        contacts_.swap_remove(p);
        if (p + 1 != moving_.size()) {
            moving_[p] = last;
            position_[last] = p;
        }
        moving_.pop_back();
    }

    /// Renumbers the per-slot arrays and the list of moving boxes as the store compacted to
    /// `slot_count` slots.
    void follow_compaction(const SlotRenumbering& renumbering, std::size_t slot_count) {
        std::vector<Slot> gone;  // positions of removed moving boxes
        renumbering.for_each_change([&](Slot old, Slot now) {
            if (now == kNoSlot) {
                if (statics_flag_[old] != 0) {
                    --statics_;
                    statics_changed_ = true;
                }
                if (filters_[old] != Filter{}) --non_default_;
                if (position_[old] != kNowhere) gone.push_back(position_[old]);
                return;
            }
            filters_[now] = filters_[old];
            statics_flag_[now] = statics_flag_[old];
            position_[now] = position_[old];
            if (position_[now] != kNowhere) moving_[position_[now]] = now;
        });
        // From the highest position down, so that the last one is never a removed box.
        std::sort(gone.begin(), gone.end(), std::greater<>());
        for (const Slot p : gone) remove_position(p, false);
        filters_.resize(slot_count);
        statics_flag_.resize(slot_count);
        position_.resize(slot_count);
    }

    void rebuild_statics(const BoxStore<Real, Dim>& store) {
        std::vector<Box<Real, Dim>> boxes;
        std::vector<BoxId> ids;
        std::vector<Filter> filters;
        boxes.reserve(statics_);
        ids.reserve(statics_);
        filters.reserve(statics_);
        for (std::size_t s = 0; s < store.slot_count(); ++s) {
            if (statics_flag_[s] == 0 || !filter_interacts(filters_[s])) continue;
            boxes.push_back(store.box_at(static_cast<Slot>(s)));
            ids.push_back(store.id_at(static_cast<Slot>(s)));
            filters.push_back(filters_[s]);
        }
        grid_.build(std::move(boxes), std::move(ids), std::move(filters));
        if (grid_.empty())
            contacts_.clear();
        else
            contacts_.track(moving_.size());
        statics_changed_ = false;
    }

    void gather(const BoxStore<Real, Dim>& store) {
        const auto box_of = [&](std::size_t p) { return store.box_at(moving_[p]); };
        const auto info_of = [&](std::size_t p) { return IdFilter{store.id_at(moving_[p]), filters_[moving_[p]]}; };
        if (classes_.split()) classes_.gather(box_of, info_of);
        // The statics' caches follow the list of moving boxes, position by position.
        const bool whole = !classes_.split() || !grid_.empty();
        moving_boxes_.gather(whole ? moving_.size() : 0, box_of, info_of);
    }

    // Per slot of the store (grown to its slot count on demand; a missing entry is the default).
    std::vector<Filter> filters_;
    std::vector<std::uint8_t> statics_flag_;
    std::vector<Slot> position_;   // in moving_, or kNowhere
    std::size_t statics_ = 0;      // slots flagged static
    std::size_t non_default_ = 0;  // slots whose filter is not the default
    PairPredicate predicate_;

    std::vector<Slot> pending_;  // slots whose flags changed since the last detection
    std::vector<Slot> moving_;   // the slots of the moving boxes, in the pipeline's index order
    std::size_t known_ = 0;      // slots this path saw at its last detection
    bool engaged_ = false;
    bool statics_changed_ = true;

    GatheredDetection<Real, Dim> moving_boxes_;  // all of them, where one class or the statics' caches want them
    StaticGrid<Real, Dim> grid_;
    StaticContacts<Real, Dim> contacts_;
    ClassDetections<Real, Dim> classes_{2};
    bool classes_stale_ = true;  // a filter value the classes do not know came in
    std::size_t since_classes_ = 0;
};

}  // namespace smb::detail
