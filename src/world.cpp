// SPDX-License-Identifier: MIT
#include "smb/world.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/collected_pairs.hpp"
#include "instantiations.hpp"
#include "query/world_query_index.hpp"
#include "world_state.hpp"

namespace smb {

bool openmp_enabled() noexcept {
#ifdef _OPENMP
    return true;
#else
    return false;
#endif
}

namespace {

/// What a moved-from world (one without a state) answers: it is empty, with default settings.
const WorldSettings kDefaultSettings{};
const DetectStats kNoStats{};
const DetectProfile kNoProfile{};

/// After the store refused an insert batch for a duplicate id: the same search the store made
/// (the first id that is in the world or earlier in the batch), to say which of the two it is.
/// Only on the error path, so the hash set costs the hot path nothing.
template <class Store>
[[noreturn]] void throw_duplicate(const Store& store, std::span<const BoxId> ids, const DuplicateIdError& error) {
    std::unordered_set<BoxId> seen;
    for (const BoxId id : ids) {
        if (store.contains(id)) break;
        if (!seen.insert(id).second)
            throw DuplicateIdError("insert: box " + std::to_string(id) +
                                   " is repeated in the batch (an insert names each id once)");
    }
    throw error;
}

/// Calls apply(filters, i, slot, slot_count) for each id and its slot, once all of them are
/// known: an unknown id throws before anything changes.
template <class State, class Apply>
void change_filters(State& state, std::span<const BoxId> ids, Apply apply) {
    const auto& store = state.store();
    for (const BoxId id : ids) (void)store.slot_of(id);
    for (std::size_t i = 0; i < ids.size(); ++i) apply(state.filters(), i, store.slot_of(ids[i]), store.slot_count());
}

/// The state of the world that holds `id`, or UnknownIdError for a world that holds nothing.
template <class State>
const State& holding(const std::unique_ptr<State>& state, BoxId id) {
    if (!state) throw UnknownIdError("box " + std::to_string(id) + " is not in the world");
    return *state;
}

}  // namespace

template <std::floating_point Real, int Dim>
World<Real, Dim>::World(const WorldSettings& settings)
    : state_(std::make_unique<detail::WorldState<Real, Dim>>(settings)) {}

template <std::floating_point Real, int Dim>
World<Real, Dim>::~World() = default;

template <std::floating_point Real, int Dim>
World<Real, Dim>::World(World&&) noexcept = default;

template <std::floating_point Real, int Dim>
World<Real, Dim>& World<Real, Dim>::operator=(World&&) noexcept = default;

template <std::floating_point Real, int Dim>
detail::WorldState<Real, Dim>& World<Real, Dim>::state() {
    if (!state_) state_ = std::make_unique<detail::WorldState<Real, Dim>>(kDefaultSettings);
    return *state_;
}

template <std::floating_point Real, int Dim>
const BoxIndex<Real, Dim>& World<Real, Dim>::query_index() {
    if (!query_index_) query_index_ = std::make_unique<detail::WorldQueryIndex<Real, Dim>>();
    auto& cache = *query_index_;
    const std::uint64_t changes = state_ ? state_->store().changes() : 0;
    if (cache.built_at == changes) return cache.index;
    const auto& store = state_->store();
    cache.index.build_from_store(store.boxes(), store.ids(),
                                 [&](std::size_t slot) { return store.alive(static_cast<detail::Slot>(slot)); });
    cache.built_at = changes;
    return cache.index;
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::query(const box_type& box, std::vector<BoxId>& out) {
    query_index().query(box, out);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::query(std::span<const box_type> queries, std::vector<QueryHit>& out) {
    query_index().query(queries, out);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::cast_ray(const Ray<Real, Dim>& ray, RayHits mode, std::vector<RayHit<Real>>& out) {
    query_index().cast_ray(ray, mode, out);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::insert(BoxId id, const box_type& box) {
    state().store().insert(std::span(&id, 1), std::span(&box, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::insert(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    auto& store = state().store();
    try {
        store.insert(ids, boxes);
    } catch (const DuplicateIdError& error) {
        throw_duplicate(store, ids, error);
    }
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::remove(BoxId id) {
    state().store().remove(std::span(&id, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::remove(std::span<const BoxId> ids) {
    state().store().remove(ids);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::update(BoxId id, const box_type& box) {
    update(std::span(&id, 1), std::span(&box, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::update(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    auto& state = this->state();
    state.store().update(ids, boxes);
    state.filters().note_updated(state.store(), ids);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::assign(std::span<const box_type> boxes) {
    auto& state = this->state();
    state.filters().note_assign(state.store(), boxes);
    state.store().assign(boxes);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::clear() {
    if (state_) state_->clear();
    query_index_.reset();  // the cleared store counts its changes from 0 again
}

template <std::floating_point Real, int Dim>
bool World<Real, Dim>::contains(BoxId id) const {
    return state_ && state_->store().contains(id);
}

template <std::floating_point Real, int Dim>
typename World<Real, Dim>::box_type World<Real, Dim>::box(BoxId id) const {
    const auto& store = holding(state_, id).store();
    return store.box_at(store.slot_of(id));
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::size() const noexcept {
    return state_ ? state_->store().size() : 0;
}

template <std::floating_point Real, int Dim>
const WorldSettings& World<Real, Dim>::settings() const noexcept {
    return state_ ? state_->settings() : kDefaultSettings;
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(std::vector<Pair>& pairs) {
    auto& state = this->state();
    return detail::collect_pairs(pairs, state.settings().max_pairs_held, "WorldSettings::max_pairs_held",
                                 "detect(sink)", [&](const PairSink& sink) { return state.detect(sink); });
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    return state().detect(sink);
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(std::vector<Pair>& pairs, PairEvents& events) {
    auto& state = this->state();
    // The events are updated inside the collection, so that a throw there restores the pairs.
    return detail::collect_pairs(pairs, state.settings().max_pairs_held, "WorldSettings::max_pairs_held",
                                 "detect(sink)", [&](const PairSink& sink) {
                                     const std::size_t kept = pairs.size();
                                     const DetectStats stats = state.detect(sink);
                                     if (state.cleared_before_detect()) events.replace_all();
                                     events.update(std::span<const Pair>(pairs).subspan(kept),
                                                   state.reinserted_before_detect());
                                     return stats;
                                 });
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs) {
    return state().detect_periodic(domain, pairs, nullptr);
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs,
                                     PairEvents& events) {
    return state().detect_periodic(domain, pairs, &events);
}

// The filters (smb/filter.hpp, docs/filters.md).

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(BoxId id, const Filter& filter) {
    set_filter(std::span(&id, 1), filter);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(std::span<const BoxId> ids, std::span<const Filter> filters) {
    if (ids.size() != filters.size())
        throw ArgumentError("set_filter: " + std::to_string(ids.size()) + " ids but " + std::to_string(filters.size()) +
                            " filters");
    change_filters(state(), ids, [&](auto& all, std::size_t i, auto slot, std::size_t count) {
        all.set_filter(slot, filters[i], count);
    });
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(std::span<const BoxId> ids, const Filter& filter) {
    change_filters(state(), ids,
                   [&](auto& all, std::size_t, auto slot, std::size_t count) { all.set_filter(slot, filter, count); });
}

template <std::floating_point Real, int Dim>
Filter World<Real, Dim>::filter(BoxId id) const {
    const auto& state = holding(state_, id);
    return state.filters().filter_at(state.store().slot_of(id));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_static(BoxId id, bool is_static) {
    set_static(std::span(&id, 1), is_static);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_static(std::span<const BoxId> ids, bool is_static) {
    change_filters(state(), ids, [&](auto& all, std::size_t, auto slot, std::size_t count) {
        all.set_static(slot, is_static, count);
    });
}

template <std::floating_point Real, int Dim>
bool World<Real, Dim>::is_static(BoxId id) const {
    const auto& state = holding(state_, id);
    return state.filters().static_at(state.store().slot_of(id));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_pair_predicate(PairPredicate predicate) {
    state().filters().set_predicate(std::move(predicate));
}

template <std::floating_point Real, int Dim>
const DetectStats& World<Real, Dim>::last_stats() const noexcept {
    return state_ ? state_->last_stats() : kNoStats;
}

template <std::floating_point Real, int Dim>
const DetectProfile& World<Real, Dim>::last_profile() const noexcept {
    return state_ ? state_->last_profile() : kNoProfile;
}

template <std::floating_point Real, int Dim>
HeldPrecision World<Real, Dim>::last_precision() const noexcept {
    return state_ ? state_->last_precision() : HeldPrecision::none;
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::last_retested_pairs() const noexcept {
    return state_ ? state_->last_retested_pairs() : 0;
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::bytes_held() const noexcept {
    return (state_ ? state_->bytes_held() : 0) + (query_index_ ? query_index_->index.bytes_held() : 0);
}

template <std::floating_point Real, int Dim>
std::vector<Pair> find_overlapping_pairs(std::span<const Box<Real, Dim>> boxes, const WorldSettings& settings) {
    World<Real, Dim> world(settings);
    world.assign(boxes);
    std::vector<Pair> pairs;
    world.detect(pairs);
    return pairs;
}

#define SMB_INSTANTIATE(Real, Dim)   \
    template class World<Real, Dim>; \
    template std::vector<Pair> find_overlapping_pairs<Real, Dim>(std::span<const Box<Real, Dim>>, const WorldSettings&);
SMB_FOR_EACH_BOX_TYPE(SMB_INSTANTIATE)
#undef SMB_INSTANTIATE

}  // namespace smb
