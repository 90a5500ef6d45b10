#include "smb/detector.hpp"

#include <functional>
#include <string>

#include "detector_state.hpp"

namespace smb {

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::Detector(const WorldSettings& settings)
    : state_(std::make_unique<detail::DetectorState<Real, Dim>>(settings)) {}

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::~Detector() = default;

template <std::floating_point Real, int Dim>
Detector<Real, Dim>::Detector(Detector&&) noexcept = default;

template <std::floating_point Real, int Dim>
Detector<Real, Dim>& Detector<Real, Dim>::operator=(Detector&&) noexcept = default;

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, std::vector<Pair>& pairs) {
    pairs.clear();
    const detail::PairCollector collector{pairs, state_->settings().max_pairs_held, "detect(boxes, sink)"};
    return state_->detect(boxes, std::cref(collector));
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PairSink& sink) {
    if (!sink) throw ArgumentError("detect: the pair sink is empty");
    return state_->detect(boxes, sink);
}

template <std::floating_point Real, int Dim>
void Detector<Real, Dim>::clear() {
    state_->clear();
}

template <std::floating_point Real, int Dim>
const WorldSettings& Detector<Real, Dim>::settings() const noexcept {
    return state_->settings();
}

template <std::floating_point Real, int Dim>
const DetectStats& Detector<Real, Dim>::last_stats() const noexcept {
    return state_->last_stats();
}

template <std::floating_point Real, int Dim>
HeldPrecision Detector<Real, Dim>::last_precision() const noexcept {
    return state_->last_precision();
}

template <std::floating_point Real, int Dim>
std::size_t Detector<Real, Dim>::last_retested_pairs() const noexcept {
    return state_->last_retested_pairs();
}

template <std::floating_point Real, int Dim>
std::size_t Detector<Real, Dim>::bytes_held() const noexcept {
    return state_->bytes_held();
}

template class Detector<float, 2>;
template class Detector<double, 2>;
template class Detector<float, 3>;
template class Detector<double, 3>;

}  // namespace smb
