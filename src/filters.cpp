// SPDX-License-Identifier: MIT
// The filter calls of World and Detector (smb/filter.hpp, docs/filters.md), apart from
// world.cpp and detector.cpp; each member is instantiated here for the four box types.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/collected_pairs.hpp"
#include "core/scene_bounds.hpp"
#include "core/stopwatch.hpp"
#include "detector_state.hpp"
#include "filters/filtered_sink.hpp"
#include "smb/detector.hpp"
#include "smb/world.hpp"
#include "world_state.hpp"

namespace smb {

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(BoxId id, const Filter& filter) {
    auto& state = this->state();
    state.filters().set_filter(state.store().slot_of(id), filter, state.store().slot_count());
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(std::span<const BoxId> ids, std::span<const Filter> filters) {
    if (ids.size() != filters.size())
        throw ArgumentError("set_filter: " + std::to_string(ids.size()) + " ids but " + std::to_string(filters.size()) +
                            " filters");
    auto& state = this->state();
    const auto& store = state.store();
    for (const BoxId id : ids) (void)store.slot_of(id);  // throws before any change
    for (std::size_t i = 0; i < ids.size(); ++i)
        state.filters().set_filter(store.slot_of(ids[i]), filters[i], store.slot_count());
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_filter(std::span<const BoxId> ids, const Filter& filter) {
    auto& state = this->state();
    const auto& store = state.store();
    for (const BoxId id : ids) (void)store.slot_of(id);  // throws before any change
    for (const BoxId id : ids) state.filters().set_filter(store.slot_of(id), filter, store.slot_count());
}

template <std::floating_point Real, int Dim>
Filter World<Real, Dim>::filter(BoxId id) const {
    if (!state_) throw UnknownIdError("box " + std::to_string(id) + " is not in the world");
    return state_->filters().filter_at(state_->store().slot_of(id));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_static(BoxId id, bool is_static) {
    set_static(std::span(&id, 1), is_static);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_static(std::span<const BoxId> ids, bool is_static) {
    auto& state = this->state();
    const auto& store = state.store();
    for (const BoxId id : ids) (void)store.slot_of(id);  // throws before any change
    for (const BoxId id : ids) state.filters().set_static(store.slot_of(id), is_static, store.slot_count());
}

template <std::floating_point Real, int Dim>
bool World<Real, Dim>::is_static(BoxId id) const {
    if (!state_) throw UnknownIdError("box " + std::to_string(id) + " is not in the world");
    return state_->filters().static_at(state_->store().slot_of(id));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::set_pair_predicate(PairPredicate predicate) {
    state().filters().set_predicate(std::move(predicate));
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const Box<Real, Dim>> boxes, const DetectFilters& filters,
                                        std::vector<Pair>& pairs) {
    detail::check_filter_lengths(filters, boxes.size());
    return detail::collect_pairs(pairs, state().settings().max_pairs_held, "DetectorSettings::max_pairs_held",
                                 "detect(boxes, filters, sink)",
                                 [&](const PairSink& sink) { return detect(boxes, filters, sink); });
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const Box<Real, Dim>> boxes, const DetectFilters& filters,
                                        const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    detail::check_filter_lengths(filters, boxes.size());
    auto& state = this->state();
    if (!detail::filters_in_use(filters)) return state.detect(boxes, sink);
    // Boxes that pair with nothing stay out of the detection. The boxes are checked first, so
    // that an invalid one is named by its index in the caller's array.
    bool gathered = false;
    if (!filters.filters.empty()) {
        const detail::Stopwatch whole;
        (void)detail::checked_bounds(boxes);
        DetectStats split;
        if (state.classes().detect(boxes, filters, sink, state.settings(), split)) {
            state.release_whole_pipeline();
            state.forget_candidates();
            split.boxes = boxes.size();
            split.bytes_held = state.bytes_held();
            split.total_seconds = whole.seconds();
            state.set_last_stats(split);
            return split;
        }
        gathered = detail::gather_interacting(boxes, filters.filters, state.gathered(), state.gathered_origin());
    }
    detail::FilteredSink filtered(
        filters, sink, state.settings().pair_chunk_size,
        gathered ? std::span<const std::uint32_t>(state.gathered_origin()) : std::span<const std::uint32_t>());
    DetectStats stats = state.detect(gathered ? std::span<const Box<Real, Dim>>(state.gathered()) : boxes,
                                     PairSink(std::ref(filtered)));
    stats.boxes = boxes.size();
    stats.pairs = filtered.finish();
    state.set_reported(stats.boxes, stats.pairs);
    if (gathered) state.forget_candidates();
    return stats;
}

#define SMB_INSTANTIATE(Real, Dim)                                                                          \
    template void World<Real, Dim>::set_filter(BoxId, const Filter&);                                       \
    template void World<Real, Dim>::set_filter(std::span<const BoxId>, std::span<const Filter>);            \
    template void World<Real, Dim>::set_filter(std::span<const BoxId>, const Filter&);                      \
    template Filter World<Real, Dim>::filter(BoxId) const;                                                  \
    template void World<Real, Dim>::set_static(BoxId, bool);                                                \
    template void World<Real, Dim>::set_static(std::span<const BoxId>, bool);                               \
    template bool World<Real, Dim>::is_static(BoxId) const;                                                 \
    template void World<Real, Dim>::set_pair_predicate(PairPredicate);                                      \
    template DetectStats Detector<Real, Dim>::detect(std::span<const Box<Real, Dim>>, const DetectFilters&, \
                                                     std::vector<Pair>&);                                   \
    template DetectStats Detector<Real, Dim>::detect(std::span<const Box<Real, Dim>>, const DetectFilters&, \
                                                     const PairSink&);

SMB_INSTANTIATE(float, 2)
SMB_INSTANTIATE(double, 2)
SMB_INSTANTIATE(float, 3)
SMB_INSTANTIATE(double, 3)

#undef SMB_INSTANTIATE

}  // namespace smb
