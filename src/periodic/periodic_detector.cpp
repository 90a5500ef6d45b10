// SPDX-License-Identifier: MIT
// Detector's periodic detections (smb/periodic.hpp): they run beside its ordinary ones, on a
// pipeline of their own (periodic/periodic_path.hpp).

#include <span>
#include <vector>

#include "detector_state.hpp"
#include "smb/detector.hpp"

namespace smb {

namespace {

/// Checks the domain before anything changes (the boxes are checked as they are gathered).
template <std::floating_point Real, int Dim>
void check_periodic_input(std::span<const Box<Real, Dim>>, const PeriodicDomain<Real, Dim>& domain) {
    check_domain(domain);
}

}  // namespace

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs) {
    auto& state = this->state();
    check_periodic_input(boxes, domain);
    state.forget_candidates();  // the Verlet list is the ordinary detections' (smb/candidate_pairs.hpp)
    const DetectStats stats =
        state.periodic().detect(boxes, {}, domain, state.settings(), pairs, state.settings().skin);
    state.set_last_stats(stats);
    return stats;
}

template <std::floating_point Real, int Dim>
DetectStats Detector<Real, Dim>::detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                                        std::vector<PeriodicPair>& pairs, PairEvents& events) {
    auto& state = this->state();
    check_periodic_input(boxes, domain);
    state.forget_candidates();  // the Verlet list is the ordinary detections' (smb/candidate_pairs.hpp)
    const DetectStats stats = state.periodic().detect(
        boxes, {}, domain, state.settings(), pairs, [&](std::span<const Pair> plain) { events.update(plain); },
        state.settings().skin);
    state.set_last_stats(stats);
    return stats;
}

#define SMB_PERIODIC_DETECTOR(R, D)                                                                      \
    template DetectStats Detector<R, D>::detect(std::span<const Box<R, D>>, const PeriodicDomain<R, D>&, \
                                                std::vector<PeriodicPair>&);                             \
    template DetectStats Detector<R, D>::detect(std::span<const Box<R, D>>, const PeriodicDomain<R, D>&, \
                                                std::vector<PeriodicPair>&, PairEvents&);

SMB_PERIODIC_DETECTOR(float, 2)
SMB_PERIODIC_DETECTOR(double, 2)
SMB_PERIODIC_DETECTOR(float, 3)
SMB_PERIODIC_DETECTOR(double, 3)

#undef SMB_PERIODIC_DETECTOR

}  // namespace smb
