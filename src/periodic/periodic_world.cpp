// SPDX-License-Identifier: MIT
// World's periodic detections (smb/periodic.hpp): the world's boxes, by slot, through a
// periodic path of its own (world_state.hpp, periodic/periodic_path.hpp).

#include <vector>

#include "smb/world.hpp"
#include "world_state.hpp"

namespace smb {

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs) {
    return state().detect_periodic(domain, pairs, nullptr);
}

template <std::floating_point Real, int Dim>
DetectStats World<Real, Dim>::detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs,
                                     PairEvents& events) {
    return state().detect_periodic(domain, pairs, &events);
}

#define SMB_PERIODIC_WORLD(R, D)                                                                       \
    template DetectStats World<R, D>::detect(const PeriodicDomain<R, D>&, std::vector<PeriodicPair>&); \
    template DetectStats World<R, D>::detect(const PeriodicDomain<R, D>&, std::vector<PeriodicPair>&, PairEvents&);

SMB_PERIODIC_WORLD(float, 2)
SMB_PERIODIC_WORLD(double, 2)
SMB_PERIODIC_WORLD(float, 3)
SMB_PERIODIC_WORLD(double, 3)

#undef SMB_PERIODIC_WORLD

}  // namespace smb
