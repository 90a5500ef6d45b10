// SPDX-License-Identifier: MIT
#include <cstdlib>
#include <string>

#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

// The Verlet grid's skin on scenes whose largest box side is 1. On the paper's scene at 300k boxes,
// Λ = 1e-5, skins 0.02, 0.05 and 0.1 took the same steady step within the noise, none rebuilding
// its list in 40 steps (bench/results/cpp-2core/grid-peers.md); 0.05 leaves a box 2.5 times the
// room of 0.02 before a rebuild, for 26% more listed candidates.
constexpr float default_verlet_skin = 0.05f;

}  // namespace

std::vector<PeerInfo> available_peers() {
    std::vector<PeerInfo> peers = {
        {"smb", true, true},
        {"smb_2threads", true, true},
        {"smb_double", true, true},
        {"smb_paper", true, true},
        {"smb_skin", true, true},
        {"smb_detector", true, true},
        {"smb_detector_sorted", true, true},
        {"smb_detector_2threads", true, true},
        {"smb_detector_skin", true, true},
        {"smb_detector_skin_2threads", true, true},
        {"brute_force", true, true},
        {"box_pruning", true, true},
        {"uniform_grid", true, true},
        {"uniform_grid_2threads", true, true},
        {"uniform_grid_sorted", true, true},
        {"verlet_grid", true, true},
        {"uniform_grid_every_cell", true, true},
    };
#if SMB_BENCH_HAVE_CGAL
    peers.push_back({"cgal_box_intersection", true, true});
#endif
#if SMB_BENCH_HAVE_BULLET
    peers.push_back({"bullet_axis_sweep", false, true});
    peers.push_back({"bullet_dbvt", false, true});
#endif
#if SMB_BENCH_HAVE_BOX2D
    peers.push_back({"box2d_dynamic_tree", true, false});
#endif
    return peers;
}

template <int Dim>
std::unique_ptr<Peer<Dim>> make_peer(std::string_view name) {
    if (name == "smb") return make_smb_world_peer<Dim>(WorldSettings{});
    if (name == "smb_2threads") {
        WorldSettings settings;
        settings.threads = 2;
        return make_smb_world_peer<Dim>(settings);
    }
    if (name == "smb_double") return make_smb_world_double_peer<Dim>(WorldSettings{});
    if (name == "smb_paper") {
        WorldSettings settings;
        settings.pipeline = Pipeline::paper_lists;
        return make_smb_world_peer<Dim>(settings);
    }
    if (name == "smb_skin") {
        WorldSettings settings;
        settings.skin = 0.1;  // as smb_detector_skin's
        return make_smb_world_peer<Dim>(settings);
    }
    if (name == "smb_detector") return make_smb_detector_peer<Dim>(DetectorSettings{});
    // A simulation that renumbers its bodies in the detector's suggested order after the build
    // and every 100 steps after it (LAMMPS sorts its atoms every 1000 by default).
    if (name == "smb_detector_sorted") return make_smb_detector_peer<Dim>(DetectorSettings{}, 100);
    if (name == "smb_detector_2threads") {
        DetectorSettings settings;
        settings.threads = 2;
        return make_smb_detector_peer<Dim>(settings);
    }
    if (name == "smb_detector_skin") {
        // Box2D's b2_aabbMargin (0.1): the same fattening as the tree peer's, on scenes whose
        // largest box side is 1.
        DetectorSettings settings;
        settings.skin = 0.1;
        return make_smb_detector_peer<Dim>(settings);
    }
    if (name == "smb_detector_skin_2threads") {
        DetectorSettings settings;
        settings.skin = 0.1;
        settings.threads = 2;
        return make_smb_detector_peer<Dim>(settings);
    }
    if (name == "brute_force") return make_brute_force_peer<Dim>();
    if (name == "box_pruning") return make_box_pruning_peer<Dim>();
    if (name == "uniform_grid") return make_uniform_grid_peer<Dim>(1);
    if (name == "uniform_grid_2threads") return make_uniform_grid_peer<Dim>(2);
    if (name == "uniform_grid_sorted") return make_sorted_uniform_grid_peer<Dim>(100);  // as smb_detector_sorted
    if (name == "verlet_grid") return make_verlet_grid_peer<Dim>(default_verlet_skin);
    // verlet_grid:SKIN, any other skin.
    if (name.starts_with("verlet_grid:")) {
        const std::string skin(name.substr(name.find(':') + 1));
        char* end = nullptr;
        const float value = std::strtof(skin.c_str(), &end);
        if (end == skin.c_str() || *end != '\0' || !(value >= 0)) return nullptr;
        return make_verlet_grid_peer<Dim>(value);
    }
    if (name == "uniform_grid_every_cell") return make_uniform_grid_every_cell_peer<Dim>();
#if SMB_BENCH_HAVE_CGAL
    if (name == "cgal_box_intersection") return make_cgal_box_intersection_peer<Dim>();
#endif
    if constexpr (Dim == 3) {
#if SMB_BENCH_HAVE_BULLET
        if (name == "bullet_axis_sweep") return make_bullet_axis_sweep_peer();
        if (name == "bullet_dbvt") return make_bullet_dbvt_peer();
#endif
    } else {
#if SMB_BENCH_HAVE_BOX2D
        if (name == "box2d_dynamic_tree") return make_box2d_dynamic_tree_peer();
#endif
    }
    return nullptr;
}

template std::unique_ptr<Peer<2>> make_peer<2>(std::string_view);
template std::unique_ptr<Peer<3>> make_peer<3>(std::string_view);

}  // namespace smb::bench
