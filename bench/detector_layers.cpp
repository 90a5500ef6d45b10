// SPDX-License-Identifier: MIT
// smb_detector_layers: a Detector's filtered detection of two layers that ignore each other,
// against the same array unfiltered and against each layer in a detector of its own.
//
// The paper's environment (3D, density 0.4, size ratio 2.5, update factor 1e-3) with 2N boxes
// in one cube, kept as an array by swap-remove (the way a simulation keeps its bodies); box i
// belongs to layer 1 or 2 by the parity of its id (Filter{1, 1} or Filter{2, 2}). Each step
// times three detections in rotating order, so that the load of a shared machine falls on all
// alike: the whole array without filters (the pairs across the layers found too), the whole
// array with the layers' filters, and the two layers' arrays each in a detector of its own (the
// layers' arrays kept outside the timing, as a simulation that keeps them apart would hold
// them, each kept by swap-remove as the whole array is). Wall clock and thread CPU, medians of the steady steps.
//
// Usage: smb_detector_layers [--moving N] [--steps S]   (N boxes per layer, default 100000)

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "smb/smb.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/swap_remove_mirror.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using Box = smb::Box<double, 3>;
using Detector = smb::Detector<double, 3>;
using smb::BoxId;

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t moving = 100000;
    int steps = 20;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--moving") == 0 && i + 1 < argc) {
            moving = std::strtoull(argv[++i], nullptr, 10);
        } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
            steps = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: smb_detector_layers [--moving N] [--steps S]\n");
            return 2;
        }
    }
    smb::workload::EnvironmentParams params;
    params.box_count = 2 * moving;
    params.packing_density = 0.4;
    params.size_ratio = 2.5;
    params.update_factor = 1e-3;
    params.seed = 3;
    smb::workload::DynamicEnvironment<3> env(params);
    smb::workload::SwapRemoveMirror<Box> mirror;
    smb::workload::SwapRemoveMirror<Box> layer_mirror[2];
    std::vector<BoxId> layer_removed[2];
    std::vector<BoxId> layer_inserted[2];
    std::vector<BoxId> layer_ids[2];

    Detector unfiltered;
    Detector layered;
    Detector separate[2];
    std::vector<smb::Filter> filters;
    std::vector<Box> layer_boxes[2];
    std::vector<smb::Pair> pairs;
    const char* names[3] = {"unfiltered", "two layers, filtered", "each layer in its own detector"};
    std::vector<double> wall[3];
    std::vector<double> cpu[3];
    std::size_t counts[3] = {0, 0, 0};
    for (int s = -1; s < steps; ++s) {
        const auto& changes = s < 0 ? env.changes() : env.step();
        mirror.follow(changes.removed_ids, changes.inserted_ids, env.ids(), env.boxes());
        filters.resize(mirror.ids().size());
        for (std::size_t i = 0; i < filters.size(); ++i)
            filters[i] = mirror.ids()[i] % 2 == 0 ? smb::Filter{1, 1} : smb::Filter{2, 2};
        for (int l = 0; l < 2; ++l) {
            layer_removed[l].clear();
            layer_inserted[l].clear();
            layer_ids[l].clear();
            layer_boxes[l].clear();
        }
        for (const BoxId id : changes.removed_ids) layer_removed[id % 2].push_back(id);
        for (const BoxId id : changes.inserted_ids) layer_inserted[id % 2].push_back(id);
        for (std::size_t i = 0; i < env.ids().size(); ++i) {
            layer_ids[env.ids()[i] % 2].push_back(env.ids()[i]);
            layer_boxes[env.ids()[i] % 2].push_back(env.boxes()[i]);
        }
        for (int l = 0; l < 2; ++l)
            layer_mirror[l].follow(layer_removed[l], layer_inserted[l], layer_ids[l], layer_boxes[l]);
        smb::DetectFilters layers;
        layers.filters = filters;
        for (int turn = 0; turn < 3; ++turn) {
            const int scene = (turn + s + 3) % 3;
            const double cpu_start = thread_seconds();
            const auto start = Clock::now();
            pairs.clear();
            if (scene == 0) {
                unfiltered.detect(mirror.boxes(), pairs);
                counts[0] = pairs.size();
            } else if (scene == 1) {
                layered.detect(mirror.boxes(), layers, pairs);
                counts[1] = pairs.size();
            } else {
                separate[0].detect(layer_mirror[0].boxes(), pairs);
                counts[2] = pairs.size();
                separate[1].detect(layer_mirror[1].boxes(), pairs);
                counts[2] += pairs.size();
            }
            if (s < 0) continue;
            wall[scene].push_back(std::chrono::duration<double>(Clock::now() - start).count());
            cpu[scene].push_back(thread_seconds() - cpu_start);
        }
    }
    std::printf("Detector, 2 x %zu boxes, %d steps after the first, rotating order (medians)\n", moving, steps);
    for (int k = 0; k < 3; ++k) {
        std::printf("  %-32s %9zu pairs  wall %8.2f ms  thread CPU %8.2f ms\n", names[k], counts[k],
                    median(wall[k]) * 1e3, median(cpu[k]) * 1e3);
    }
    std::printf("  filtered / separate: wall %.2f, CPU %.2f; filtered / unfiltered: wall %.2f, CPU %.2f\n",
                median(wall[1]) / median(wall[2]), median(cpu[1]) / median(cpu[2]), median(wall[1]) / median(wall[0]),
                median(cpu[1]) / median(cpu[0]));
    return counts[1] == counts[2] ? 0 : 1;
}
