// SPDX-License-Identifier: MIT
#include "smb/detector.hpp"

#include <functional>
#include <span>
#include <vector>

#include "core/collected_pairs.hpp"
#include "detector_state.hpp"
#include "filters/filtered_sink.hpp"
#include "instantiations.hpp"

namespace smb {

namespace {

/// What a moved-from detector (one without a state) answers: it holds nothing, with default
/// settings.
const DetectorSettings kDefaultSettings{};
const DetectStats kNoStats{};
const DetectProfile kNoProfile{};

}  // namespace

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::Detector(const DetectorSettings& settings)
    : state_(std::make_unique<detail::DetectorState<Real, Dim>>(settings)) {}

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::~Detector() = default;

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::Detector(Detector&&) noexcept = default;

template <std::floating_point Real, int Dim>
Detector<Real, Dim>& Detector<Real, Dim>::operator=(Detector&&) noexcept = default;

template <std::floating_point Real, int Dim>
detail::DetectorState<Real, Dim>& Detector<Real, Dim>::state() {
    if (!state_) state_ = std::make_unique<detail::DetectorState<Real, Dim>>(kDefaultSettings);
    return *state_;
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, std::vector<Pair>& pairs) {
    auto& state = this->state();
    return detail::collect_pairs(pairs, state.settings().max_pairs_held, "DetectorSettings::max_pairs_held",
                                 "detect(boxes, sink)",
                                 [&](const PairSink& sink) { return state.detect(boxes, sink); });
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    return state().detect(boxes, sink);
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, std::vector<Pair>& pairs, PairEvents& events) {
    auto& state = this->state();
    // The events are updated inside the collection, so that a throw there restores the pairs.
    return detail::collect_pairs(pairs, state.settings().max_pairs_held, "DetectorSettings::max_pairs_held",
                                 "detect(boxes, sink)", [&](const PairSink& sink) {
                                     const std::size_t kept = pairs.size();
                                     const DetectStats stats = state.detect(boxes, sink);
                                     events.update(std::span<const Pair>(pairs).subspan(kept));
                                     return stats;
                                 });
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const DetectFilters& filters,
                                        std::vector<Pair>& pairs) {
    detail::check_filter_lengths(filters, boxes.size());
    auto& state = this->state();
    return detail::collect_pairs(pairs, state.settings().max_pairs_held, "DetectorSettings::max_pairs_held",
                                 "detect(boxes, filters, sink)",
                                 [&](const PairSink& sink) { return state.detect_filtered(boxes, filters, sink); });
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const DetectFilters& filters,
                                        const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    detail::check_filter_lengths(filters, boxes.size());
    return state().detect_filtered(boxes, filters, sink);
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs) {
    return state().detect_periodic(boxes, domain, pairs);
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs, PairEvents& events) {
    return state().detect_periodic(boxes, domain, pairs, [&](std::span<const Pair> plain) { events.update(plain); });
}

template <std::floating_point Real, int Dim>
std::span<const std::uint32_t> Detector<Real, Dim>::suggested_order() const noexcept {
    return state_ ? state_->suggested_order() : std::span<const std::uint32_t>();
}

template <std::floating_point Real, int Dim>
void Detector<Real, Dim>::follow_suggested_order() {
    if (state_) state_->follow_suggested_order();
}

template <std::floating_point Real, int Dim>
void Detector<Real, Dim>::clear() {
    if (state_) state_->clear();
}

template <std::floating_point Real, int Dim>
const DetectorSettings& Detector<Real, Dim>::settings() const noexcept {
    return state_ ? state_->settings() : kDefaultSettings;
}

template <std::floating_point Real, int Dim>
const DetectStats& Detector<Real, Dim>::last_stats() const noexcept {
    return state_ ? state_->last_stats() : kNoStats;
}

template <std::floating_point Real, int Dim>
const DetectProfile& Detector<Real, Dim>::last_profile() const noexcept {
    return state_ ? state_->last_profile() : kNoProfile;
}

template <std::floating_point Real, int Dim>
HeldPrecision Detector<Real, Dim>::last_precision() const noexcept {
    return state_ ? state_->last_precision() : HeldPrecision::none;
}

template <std::floating_point Real, int Dim>
std::size_t Detector<Real, Dim>::last_retested_pairs() const noexcept {
    return state_ ? state_->last_retested_pairs() : 0;
}

template <std::floating_point Real, int Dim>
std::size_t Detector<Real, Dim>::bytes_held() const noexcept {
    return state_ ? state_->bytes_held() : 0;
}

template <std::floating_point Real, int Dim>
CandidatePairs Detector<Real, Dim>::candidates() {
    return state_ ? state_->candidates() : CandidatePairs{};
}

#define SMB_INSTANTIATE(Real, Dim) template class Detector<Real, Dim>;
SMB_FOR_EACH_BOX_TYPE(SMB_INSTANTIATE)
#undef SMB_INSTANTIATE

}  // namespace smb
