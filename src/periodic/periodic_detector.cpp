// SPDX-License-Identifier: MIT
// Detector's periodic detections (smb/periodic.hpp): they run beside its ordinary ones, on a
// pipeline of their own (periodic/periodic_path.hpp).

#include <span>
#include <vector>

#include "detector_state.hpp"
#include "periodic/periodic_images.hpp"
#include "smb/detector.hpp"

namespace smb {

namespace {

/// Checks the domain and every box before anything changes.
template <std::floating_point Real, int Dim>
void check_periodic_input(std::span<const Box<Real, Dim>> boxes, const PeriodicDomain<Real, Dim>& domain) {
    check_domain(domain);
    detail::PeriodicImages<Real, Dim>::check(
        boxes, domain, [](std::size_t) { return true; }, [](std::size_t i) { return static_cast<BoxId>(i); });
}

}  // namespace

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs) {
    auto& state = this->state();
    check_periodic_input(boxes, domain);
    const DetectStats stats = state.periodic().detect(boxes, {}, domain, state.settings(), pairs);
    state.set_last_stats(stats);
    return stats;
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs, PairEvents& events) {
    auto& state = this->state();
    check_periodic_input(boxes, domain);
    const DetectStats stats = state.periodic().detect(
        boxes, {}, domain, state.settings(), pairs, [&](std::span<const Pair> plain) { events.update(plain); });
    state.set_last_stats(stats);
    return stats;
}

#define SMB_PERIODIC_DETECTOR(R, D)                                                                              \
    template DetectStats Detector<R, D>::detect(std::span<const Box<R, D>>, const PeriodicDomain<R, D>&,         \
                                                std::vector<PeriodicPair>&);                                     \
    template DetectStats Detector<R, D>::detect(std::span<const Box<R, D>>, const PeriodicDomain<R, D>&,         \
                                                std::vector<PeriodicPair>&, PairEvents&);

SMB_PERIODIC_DETECTOR(float, 2)
SMB_PERIODIC_DETECTOR(double, 2)
SMB_PERIODIC_DETECTOR(float, 3)
SMB_PERIODIC_DETECTOR(double, 3)

#undef SMB_PERIODIC_DETECTOR

}  // namespace smb
