// SPDX-License-Identifier: MIT
// smb_check_grid_peers: the grid peers (one and two threads, the Verlet-skin grid at several
// skins, and the grid and smb's Detector over arrays renumbered in their own orders) against
// testing every pair, on every scene family of the comparison in 2D and 3D, at
// each step of a short run with moves, insertions and removals: slow motion (Λ = 1e-3) and fast
// (Λ = 0.05, where boxes leave their skins and many are inserted and removed). Exit status 1 on a
// difference.

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "peers/peer_factories.hpp"
#include "scenes/scene.hpp"

namespace smb::bench {
namespace {

struct Case {
    std::string family;
    int dimension = 3;
    std::size_t boxes = 1500;
};

template <int Dim>
int check(const Case& one, double update_factor, std::size_t steps) {
    SceneSpec spec;
    spec.family = one.family;
    spec.dimension = Dim;
    spec.boxes = one.boxes;
    spec.update_factor = update_factor;
    spec.seed = 7;
    std::unique_ptr<Scene<Dim>> scene;
    try {
        scene = make_scene<Dim>(spec);
    } catch (const std::invalid_argument&) {
        return 0;  // a family this build or this dimension lacks
    }
    const std::vector<std::string> names = {"uniform_grid",       "uniform_grid_2threads", "verlet_grid 0",
                                            "verlet_grid 0.02",   "verlet_grid 0.3",       "uniform_grid_sorted",
                                            "smb_detector_sorted"};
    std::vector<std::unique_ptr<Peer<Dim>>> peers;
    peers.push_back(make_uniform_grid_peer<Dim>(1));
    peers.push_back(make_uniform_grid_peer<Dim>(2));
    peers.push_back(make_verlet_grid_peer<Dim>(0.0f));
    peers.push_back(make_verlet_grid_peer<Dim>(0.02f));
    peers.push_back(make_verlet_grid_peer<Dim>(0.3f));
    // The arrays renumbered every third step, so that each run renumbers several times.
    peers.push_back(make_sorted_uniform_grid_peer<Dim>(3));
    peers.push_back(make_smb_detector_peer<Dim>(DetectorSettings{}, 3));
    auto reference = make_brute_force_peer<Dim>();
    std::vector<Pair> expected, found;
    int failures = 0;
    for (std::size_t index = 0; index <= steps; ++index) {
        const SceneStep<Dim>& step = scene->advance();
        if (index == 0)
            reference->build(step, expected);
        else
            reference->step(step, expected);
        std::sort(expected.begin(), expected.end());
        for (std::size_t p = 0; p < peers.size(); ++p) {
            found.clear();
            peers[p]->prepare(step);
            if (index == 0)
                peers[p]->build(step, found);
            else
                peers[p]->step(step, found);
            std::sort(found.begin(), found.end());
            if (found != expected) {
                std::printf("%s %dD Λ=%g step %zu: %s found %zu pairs, expected %zu\n", one.family.c_str(), Dim,
                            update_factor, index, names[p].c_str(), found.size(), expected.size());
                ++failures;
            }
        }
    }
    return failures;
}

}  // namespace
}  // namespace smb::bench

int main() {
    using smb::bench::Case;
    const std::vector<Case> cases = {
        {"paper", 3, 5000}, {"paper", 2},   {"sparse", 3},      {"clustered", 3},   {"clustered", 2},
        {"mixed", 3},       {"mixed", 2},   {"loguniform2", 3}, {"loguniform2", 2}, {"loguniform3", 3},
        {"loguniform3", 2}, {"islands", 3}, {"islands", 2},     {"plane", 3},       {"plane", 2},
        {"rods", 3},        {"rods", 2},
    };
    int failures = 0;
    for (const Case& one : cases) {
        for (const double update_factor : {1e-3, 0.05}) {
            const std::size_t steps = one.boxes > 2000 ? 6 : 20;
            failures += one.dimension == 3 ? smb::bench::check<3>(one, update_factor, steps)
                                           : smb::bench::check<2>(one, update_factor, steps);
        }
    }
    std::printf("grid peers against every pair: %d difference(s)\n", failures);
    return failures == 0 ? 0 : 1;
}
