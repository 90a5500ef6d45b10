// SPDX-License-Identifier: MIT
#include "smb/detector.hpp"

#include <functional>
#include <string>

#include "core/collected_pairs.hpp"
#include "core/scene_bounds.hpp"
#include "detector_state.hpp"
#include "filters/filtered_sink.hpp"

namespace smb {

namespace {

/// What a moved-from detector (one without a state) answers: it holds nothing, with default
/// settings.
const DetectorSettings kDefaultSettings{};
const DetectStats kNoStats{};

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
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const DetectFilters& filters,
                                        std::vector<Pair>& pairs) {
    detail::check_filter_lengths(filters, boxes.size());
    return detail::collect_pairs(pairs, state().settings().max_pairs_held, "DetectorSettings::max_pairs_held",
                                 "detect(boxes, filters, sink)",
                                 [&](const PairSink& sink) { return detect(boxes, filters, sink); });
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const DetectFilters& filters,
                                        const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    detail::check_filter_lengths(filters, boxes.size());
    auto& state = this->state();
    if (!detail::filters_in_use(filters)) return state.detect(boxes, sink);
    // Boxes that pair with nothing stay out of the detection. The boxes are checked first, so
    // that an invalid one is named by its index in the caller's array.
    bool gathered = false;
    if (!filters.filters.empty()) {
        (void)detail::checked_bounds(boxes);
        gathered = detail::gather_interacting(boxes, filters.filters, state.gathered(), state.gathered_origin());
    }
    detail::FilteredSink filtered(
        filters, sink, state.settings().pair_chunk_size,
        gathered ? std::span<const std::uint32_t>(state.gathered_origin()) : std::span<const std::uint32_t>());
    DetectStats stats =
        state.detect(gathered ? std::span<const box_type>(state.gathered()) : boxes, PairSink(std::ref(filtered)));
    stats.boxes = boxes.size();
    stats.pairs = filtered.finish();
    state.set_reported(stats.boxes, stats.pairs);
    return stats;
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

template class Detector<float, 2>;
template class Detector<double, 2>;
template class Detector<float, 3>;
template class Detector<double, 3>;

}  // namespace smb
