#include "smb/world.hpp"

#include <functional>
#include <string>
#include <utility>

#include "world_state.hpp"

namespace smb {

bool openmp_enabled() noexcept {
#ifdef _OPENMP
    return true;
#else
    return false;
#endif
}

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
void World<Real, Dim>::insert(BoxId id, const box_type& box) {
    state_->store().insert(std::span(&id, 1), std::span(&box, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::insert(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    state_->store().insert(ids, boxes);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::remove(BoxId id) {
    state_->store().remove(std::span(&id, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::remove(std::span<const BoxId> ids) {
    state_->store().remove(ids);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::update(BoxId id, const box_type& box) {
    state_->store().update(std::span(&id, 1), std::span(&box, 1));
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::update(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    state_->store().update(ids, boxes);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::assign(std::span<const box_type> boxes) {
    state_->store().assign(boxes);
}

template <std::floating_point Real, int Dim>
void World<Real, Dim>::clear() {
    state_->clear();
}

template <std::floating_point Real, int Dim>
bool World<Real, Dim>::contains(BoxId id) const {
    return state_->store().contains(id);
}

template <std::floating_point Real, int Dim>
typename World<Real, Dim>::box_type World<Real, Dim>::box(BoxId id) const {
    const auto& store = state_->store();
    return store.box_at(store.slot_of(id));
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::size() const noexcept {
    return state_->store().size();
}

template <std::floating_point Real, int Dim>
const WorldSettings& World<Real, Dim>::settings() const noexcept {
    return state_->settings();
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(std::vector<Pair>& pairs) {
    pairs.clear();
    const detail::PairCollector collector{pairs, state_->settings().max_pairs_held, "detect(sink)"};
    return state_->detect(std::cref(collector));
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    return state_->detect(sink);
}

template <std::floating_point Real, int Dim>
const DetectStats& World<Real, Dim>::last_stats() const noexcept {
    return state_->last_stats();
}

template <std::floating_point Real, int Dim>
HeldPrecision World<Real, Dim>::last_precision() const noexcept {
    return state_->last_precision();
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::last_retested_pairs() const noexcept {
    return state_->last_retested_pairs();
}

template <std::floating_point Real, int Dim>
std::size_t World<Real, Dim>::bytes_held() const noexcept {
    return state_->bytes_held();
}

template <std::floating_point Real, int Dim>
std::vector<Pair> find_overlapping_pairs(std::span<const Box<Real, Dim>> boxes,
                                         const WorldSettings& settings) {
    World<Real, Dim> world(settings);
    world.assign(boxes);
    std::vector<Pair> pairs;
    world.detect(pairs);
    return pairs;
}

#define SMB_INSTANTIATE(Real, Dim)                                                        \
    template class World<Real, Dim>;                                                      \
    template std::vector<Pair> find_overlapping_pairs<Real, Dim>(std::span<const Box<Real, Dim>>, \
                                                                 const WorldSettings&);

SMB_INSTANTIATE(float, 2)
SMB_INSTANTIATE(double, 2)
SMB_INSTANTIATE(float, 3)
SMB_INSTANTIATE(double, 3)

#undef SMB_INSTANTIATE

}  // namespace smb
