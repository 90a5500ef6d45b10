// SPDX-License-Identifier: MIT
// Google Benchmark of one smb::World (and of one smb::Detector): the time of detect() per step
// on the paper's dynamic environment and on the edge scenes of docs/algorithm.md. Only detect() is timed (manual
// time from DetectStats): generating the scene and feeding the world are outside.
//
//   build/bench/smb_bench_world --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "smb/smb.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/swap_remove_mirror.hpp"
#include "smb/workload/world_sync.hpp"

namespace {

/// The stats of a detection and its profile (the settings ask for it).
void report(benchmark::State& state, const smb::DetectStats& stats, const smb::DetectProfile& profile) {
    state.SetIterationTime(stats.total_seconds);
    state.counters["pairs"] = static_cast<double>(stats.pairs);
    state.counters["bytes_per_box"] =
        stats.boxes ? static_cast<double>(stats.bytes_held) / static_cast<double>(stats.boxes) : 0.0;
    state.counters["scan_ms"] = 1e3 * profile.scan_seconds;
    state.counters["quantile_ms"] = 1e3 * profile.quantile_seconds;
    state.counters["cut_regroup_ms"] = 1e3 * profile.cut_regroup_seconds;
    state.counters["check_ms"] = 1e3 * profile.check_seconds;
    state.counters["oversized"] = static_cast<double>(profile.oversized_boxes);
}

/// The paper's environment for args N and Λ·1e6.
smb::workload::EnvironmentParams paper_params(const benchmark::State& state) {
    smb::workload::EnvironmentParams params;
    params.box_count = static_cast<std::size_t>(state.range(0));
    params.update_factor = static_cast<double>(state.range(1)) * 1e-6;
    return params;
}

smb::WorldSettings profiled_world() {
    smb::WorldSettings settings;
    settings.profile = true;
    return settings;
}

/// The paper's environment: args are N and Λ·1e6.
template <int Dim>
void paper_step(benchmark::State& state) {
    smb::workload::DynamicEnvironment<Dim> environment(paper_params(state));
    smb::World<double, Dim> world(profiled_world());
    world.insert(environment.ids(), environment.boxes());
    std::vector<smb::Pair> pairs;
    world.detect(pairs);  // the build step is not what this measures
    for (auto _ : state) {
        smb::workload::apply_changes(environment.step(), world);
        pairs.clear();  // the old pairs are not kept: detect() has none to move
        const smb::DetectStats stats = world.detect(pairs);
        report(state, stats, world.last_profile());
    }
}
BENCHMARK(paper_step<3>)
    ->ArgNames({"N", "Lambda_e6"})
    ->Args({100000, 1000})
    ->Args({200000, 1000})
    ->Args({200000, 10000})
    ->Args({200000, 100000})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(paper_step<2>)
    ->ArgNames({"N", "Lambda_e6"})
    ->Args({200000, 1000})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

/// The same environment through smb::Detector over an array in which each body keeps its index
/// (kept outside the timing, as the simulation's own array would be): args are N and Λ·1e6.
template <int Dim>
void paper_step_detector(benchmark::State& state) {
    smb::workload::DynamicEnvironment<Dim> environment(paper_params(state));
    smb::DetectorSettings settings;
    settings.profile = true;
    if (state.range(2) > 0) settings.skin = static_cast<double>(state.range(2)) * 1e-3;
    smb::workload::SwapRemoveMirror<smb::Box<double, Dim>> mirror;
    auto follow = [&] {
        const auto& changes = environment.changes();
        mirror.follow(changes.removed_ids, changes.inserted_ids, environment.ids(), environment.boxes());
    };
    follow();
    smb::Detector<double, Dim> detector(settings);
    std::vector<smb::Pair> pairs;
    detector.detect(mirror.boxes(), pairs);  // the build step is not what this measures
    for (auto _ : state) {
        environment.step();
        follow();
        pairs.clear();  // the old pairs are not kept: detect() has none to move
        const smb::DetectStats stats = detector.detect(mirror.boxes(), pairs);
        report(state, stats, detector.last_profile());
        state.counters["skin_rebuilt"] = stats.skin_rebuilt ? 1 : 0;
    }
}
// Args: N, Λ·1e6, and the skin (DetectorSettings::skin) in thousandths, 0 for none.
BENCHMARK(paper_step_detector<3>)
    ->ArgNames({"N", "Lambda_e6", "skin_e3"})
    ->Args({100000, 1000, 0})
    ->Args({200000, 1000, 0})
    ->Args({200000, 10000, 0})
    ->Args({200000, 100000, 0})
    ->Args({200000, 10, 0})
    ->Args({200000, 10, 100})
    ->Args({200000, 1000, 100})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(paper_step_detector<2>)
    ->ArgNames({"N", "Lambda_e6", "skin_e3"})
    ->Args({200000, 1000, 0})
    ->Args({200000, 10, 0})
    ->Args({200000, 10, 100})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

/// Scenes of the deviations in docs/algorithm.md, 3D, N = arg boxes of sides in [0.4, 1].
enum class EdgeScene { kLayer, kFloor, kWalls, kJump, kIdentical };

std::vector<smb::Box3d> edge_boxes(EdgeScene scene, std::size_t n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double side = std::cbrt(static_cast<double>(n) * 0.343 / 0.4);  // E = 0.4
    std::vector<smb::Box3d> boxes(n);
    for (auto& box : boxes) {
        for (int k = 0; k < 3; ++k) {
            const double centre = unit(rng) * side;
            const double length = 0.4 + 0.6 * unit(rng);
            box.min[k] = centre - length / 2;
            box.max[k] = centre + length / 2;
        }
    }
    switch (scene) {
        case EdgeScene::kLayer: {  // every box flat on z = 0, E = 0.4 in the plane
            const double plane_side = std::sqrt(static_cast<double>(n) * 0.49 / 0.4);
            for (auto& box : boxes) {
                for (int k = 0; k < 2; ++k) {
                    const double centre = unit(rng) * plane_side;
                    const double length = 0.4 + 0.6 * unit(rng);
                    box.min[k] = centre - length / 2;
                    box.max[k] = centre + length / 2;
                }
                box.min[2] = 0.0;
                box.max[2] = 0.0;
            }
            break;
        }
        case EdgeScene::kFloor:
            for (auto& box : boxes) {
                box.min[2] += 1.0;
                box.max[2] += 1.0;
            }
            boxes[0] = smb::Box3d{{-1, -1, 0}, {side + 1, side + 1, 1.2}};
            break;
        case EdgeScene::kWalls:
            boxes[0] = smb::Box3d{{side / 2, -1, -1}, {side / 2 + 0.1, side + 1, side + 1}};
            boxes[1] = smb::Box3d{{-1, side / 2, -1}, {side + 1, side / 2 + 0.1, side + 1}};
            break;
        case EdgeScene::kIdentical:
            for (auto& box : boxes) box = smb::Box3d{{0, 0, 0}, {1, 1, 1}};
            break;
        case EdgeScene::kJump:
            break;
    }
    return boxes;
}

/// Steady steps of a static edge scene; for kJump every step re-places every box at random.
void edge_scene(benchmark::State& state, EdgeScene scene) {
    const auto n = static_cast<std::size_t>(state.range(0));
    std::mt19937_64 rng(42);
    smb::World3d world(profiled_world());
    world.assign(edge_boxes(scene, n, rng));
    std::vector<smb::Pair> pairs;
    world.detect(pairs);
    for (auto _ : state) {
        if (scene == EdgeScene::kJump) {
            state.PauseTiming();
            world.assign(edge_boxes(scene, n, rng));
            state.ResumeTiming();
        }
        pairs.clear();  // the old pairs are not kept: detect() has none to move
        const smb::DetectStats stats = world.detect(pairs);
        report(state, stats, world.last_profile());
    }
}
BENCHMARK_CAPTURE(edge_scene, layer, EdgeScene::kLayer)
    ->Arg(200000)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(edge_scene, floor, EdgeScene::kFloor)
    ->Arg(200000)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(edge_scene, walls, EdgeScene::kWalls)
    ->Arg(200000)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(edge_scene, jump, EdgeScene::kJump)
    ->Arg(200000)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(edge_scene, identical, EdgeScene::kIdentical)
    ->Arg(5000)
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
