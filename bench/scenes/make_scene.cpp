// SPDX-License-Identifier: MIT
#include <sstream>
#include <stdexcept>

#include "scenes/clustered.hpp"
#include "scenes/islands.hpp"
#include "scenes/log_uniform_sizes.hpp"
#include "scenes/mixed_sizes.hpp"
#include "scenes/plane.hpp"
#include "scenes/rods.hpp"
#include "scenes/scene.hpp"
#if SMB_BENCH_HAVE_WORKLOAD
#include "scenes/paper_environment.hpp"
#endif

namespace smb::bench {

std::string scene_label(const SceneSpec& spec) {
    std::ostringstream label;
    label << spec.family << spec.dimension << "d-L" << spec.update_factor;
    return label.str();
}

template <int Dim>
std::unique_ptr<Scene<Dim>> make_scene(const SceneSpec& spec) {
    if (spec.dimension != Dim) throw std::invalid_argument("scene dimension does not match");
    if (spec.family == "clustered") return make_clustered_scene<Dim>(spec);
    if (spec.family == "mixed") return make_mixed_sizes_scene<Dim>(spec);
    if (spec.family == "loguniform2") return make_log_uniform_sizes_scene<Dim>(spec, 2);
    if (spec.family == "loguniform3") return make_log_uniform_sizes_scene<Dim>(spec, 3);
    if (spec.family == "islands") return make_islands_scene<Dim>(spec);
    if (spec.family == "plane") return make_plane_scene<Dim>(spec);
    if (spec.family == "rods") return make_rods_scene<Dim>(spec);
#if SMB_BENCH_HAVE_WORKLOAD
    if (spec.family == "paper") return make_paper_scene<Dim>(spec);
    if constexpr (Dim == 3) {
        if (spec.family == "sparse") return make_sparse_scene(spec);
    }
#endif
    throw std::invalid_argument("no scene family '" + spec.family + "' in " + std::to_string(Dim) + "D in this build");
}

template std::unique_ptr<Scene<2>> make_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_scene<3>(const SceneSpec&);

}  // namespace smb::bench
