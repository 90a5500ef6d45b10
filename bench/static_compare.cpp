// SPDX-License-Identifier: MIT
// Static boxes and filters, side by side with the default detection, on the paper's environment
// (workload/): 3D, density 0.4, size ratio 2.5, Λ = 1e-3, World<double, 3>. Each line times a
// step (the world's update calls plus detect()), the first step apart from the median of the
// steady ones. Scenes:
//   plain        the moving boxes alone, in a World without filters (the default detection)
//   all-pass     the same, every box given a filter that differs from the default but passes
//                every pair (category 3): the filtered path's own cost
//   statics      the same moving boxes plus a second placement of static boxes (its own cube
//                at the same density, the moving cube in its middle), never updated
//   layers       twice the moving boxes in one cube, as two layers (categories 1 and 2, each
//                with the mask of its own) that ignore each other; beside it the same boxes
//                with no filters, and one layer alone
// Usage: smb_static_compare [--moving N] [--statics N] [--steps S] [--paired [--terrain]] [--layers]
//   --paired     only the plain and statics scenes, in lockstep: each step runs both worlds,
//                in alternating order, so that the load of a shared machine falls on both
//                alike; prints their medians and the median of the per-step ratios
//   --terrain    with --paired, the statics are a terrain instead of a second placement: a
//                height field of N boxes (a square grid of cells as wide as a moving box on
//                average, each cell's box spanning the heights of its corners, as a mesh's
//                triangles would), centred under the moving cube and far wider than it, its mean
//                height in the middle of the cube: the moving boxes near the surface meet it,
//                the others (most) meet no static
//   --layers     only the layers scene, in lockstep: 2N boxes as two layers that ignore each
//                other in one World, the same boxes unfiltered in another, and each layer in a
//                World of its own (the separate detections, timed together); each step runs the
//                three in rotating order and prints their medians and the medians of the ratios

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <span>
#include <string>
#include <vector>

#include "smb/smb.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/world_sync.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using smb::BoxId;
using World = smb::World3d;
using Env = smb::workload::DynamicEnvironment<3>;

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// This thread's CPU seconds: on a machine shared beyond its cores, the time a one-thread
/// detection ran, where the wall clock also counts the time others held the core.
double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

struct Timing {
    double first = 0;
    double steady = 0;
    double steady_update = 0;
    std::size_t pairs = 0;
    std::size_t boxes = 0;
    std::size_t bytes = 0;
    std::size_t refreshed = 0;  // moving boxes that asked the statics' grid again, all steps
    std::size_t cached = 0;     // static copies the moving boxes hold, last step
};

smb::workload::EnvironmentParams params(std::size_t count, std::uint64_t seed) {
    smb::workload::EnvironmentParams p;
    p.box_count = count;
    p.packing_density = 0.4;
    p.size_ratio = 2.5;
    p.update_factor = 1e-3;
    p.seed = seed;
    return p;
}

/// Runs `steps` steps of `env` in `world` (which may hold other boxes already); `prepare` is
/// called after step 0's boxes are in, before the first detection (filters go there).
template <class Prepare>
Timing run(Env& env, World& world, int steps, Prepare&& prepare) {
    Timing t;
    std::vector<smb::Pair> pairs;
    auto start = Clock::now();
    smb::workload::apply_changes(env.changes(), world);
    prepare(env.changes().inserted_ids);
    world.detect(pairs);
    t.first = since(start);
    pairs.clear();
    std::vector<double> step_times, update_times;
    for (int s = 0; s < steps; ++s) {
        const auto& changes = env.step();
        start = Clock::now();
        smb::workload::apply_changes(changes, world);
        const double updated = since(start);
        prepare(changes.inserted_ids);
        pairs.clear();  // a caller with no use for the old pairs: detect() then moves none
        const smb::DetectStats stats = world.detect(pairs);
        step_times.push_back(since(start));
        t.refreshed += stats.static_refreshed;
        t.cached = stats.static_contacts;
        update_times.push_back(updated);
    }
    t.steady = median(step_times);
    t.steady_update = median(update_times);
    t.pairs = pairs.size();
    t.boxes = world.size();
    t.bytes = world.bytes_held();
    return t;
}

void print(const char* scene, const Timing& t) {
    std::printf("| %-28s | %9zu | %9zu | %9.1f | %9.2f | %9.2f | %7.1f | %9zu | %9zu |\n", scene, t.boxes, t.pairs,
                t.first * 1e3, t.steady * 1e3, t.steady_update * 1e3, static_cast<double>(t.bytes) / 1048576.0,
                t.refreshed, t.cached);
    std::fflush(stdout);
}

/// The statics scene: `statics` boxes of a second placement (seed 2) around the cube of `env`,
/// with ids from 2^40 up, inserted in `world` and made static. Returns the seconds the insert
/// and set_static took.
double insert_statics(const Env& env, std::size_t statics, World& world) {
    const Env placement(params(statics, 2));
    const double offset = 0.5 * (placement.cube_side() - env.cube_side());
    std::vector<smb::Box3d> boxes(placement.boxes().begin(), placement.boxes().end());
    for (smb::Box3d& b : boxes) {
        for (int k = 0; k < 3; ++k) {
            b.min[k] -= offset;
            b.max[k] -= offset;
        }
    }
    std::vector<BoxId> ids(boxes.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = (BoxId{1} << 40) + i;
    const auto start = Clock::now();
    world.insert(ids, boxes);
    world.set_static(ids, true);
    return since(start);
}

/// The terrain scene (--terrain): `statics` boxes on a square grid of cells as wide as the mean
/// moving box (L (E / N)^(1/3) for the cube [0, L]^3 of N boxes at density E), centred under the
/// cube; the height is L/2 + (L/8) sin(3 pi x / L) cos(3 pi y / L) (waves two thirds of the cube
/// long), each cell's box spanning the heights of its four corners.
double insert_terrain(const Env& env, std::size_t moving, std::size_t statics, World& world) {
    const double side = env.cube_side();
    const auto n = static_cast<std::size_t>(std::sqrt(static_cast<double>(statics)));
    const double cell = side * std::cbrt(0.4 / static_cast<double>(moving));
    const double across = cell * static_cast<double>(n);
    const double pi = 3.14159265358979323846;
    const auto height = [&](double x, double y) {
        return 0.5 * side + 0.125 * side * std::sin(3 * pi * x / side) * std::cos(3 * pi * y / side);
    };
    std::vector<smb::Box3d> boxes;
    boxes.reserve(n * n);
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < n; ++i) {
            const double x0 = 0.5 * (side - across) + cell * static_cast<double>(i);
            const double y0 = 0.5 * (side - across) + cell * static_cast<double>(j);
            const double h[4] = {height(x0, y0), height(x0 + cell, y0), height(x0, y0 + cell),
                                 height(x0 + cell, y0 + cell)};
            smb::Box3d b;
            b.min = {x0, y0, *std::min_element(h, h + 4)};
            b.max = {x0 + cell, y0 + cell, *std::max_element(h, h + 4)};
            boxes.push_back(b);
        }
    }
    std::vector<BoxId> ids(boxes.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = (BoxId{1} << 40) + i;
    const auto start = Clock::now();
    world.insert(ids, boxes);
    world.set_static(ids, true);
    return since(start);
}

/// The plain and statics scenes in lockstep (--paired).
int run_paired(std::size_t moving, std::size_t statics, int steps, bool terrain) {
    Env plain_env(params(moving, 1));
    Env statics_env(params(moving, 1));
    World plain;
    World with_statics;
    if (terrain) {
        insert_terrain(statics_env, moving, statics, with_statics);
    } else {
        insert_statics(statics_env, statics, with_statics);
    }
    std::vector<smb::Pair> pairs;
    std::vector<double> plain_times, statics_times, ratios;
    std::size_t plain_pairs = 0, statics_pairs = 0;
    for (int s = -1; s < steps; ++s) {
        const bool first = s < 0;
        const auto& plain_changes = first ? plain_env.changes() : plain_env.step();
        const auto& statics_changes = first ? statics_env.changes() : statics_env.step();
        double times[2] = {0, 0};
        for (int turn = 0; turn < 2; ++turn) {
            const bool do_plain = (turn == 0) == (s % 2 == 0);
            World& world = do_plain ? plain : with_statics;
            pairs.clear();
            const auto start = Clock::now();
            smb::workload::apply_changes(do_plain ? plain_changes : statics_changes, world);
            world.detect(pairs);
            times[do_plain ? 0 : 1] = since(start);
            (do_plain ? plain_pairs : statics_pairs) = pairs.size();
        }
        if (first) continue;
        plain_times.push_back(times[0]);
        statics_times.push_back(times[1]);
        ratios.push_back(times[1] / times[0]);
    }
    std::printf(
        "paired%s, %d steps, alternating order: plain %.2f ms (%zu pairs), moving + statics %.2f ms (%zu pairs),"
        " ratio of medians %.2f, median of per-step ratios %.2f\n",
        terrain ? " (terrain)" : "", steps, median(plain_times) * 1e3, plain_pairs, median(statics_times) * 1e3,
        statics_pairs, median(statics_times) / median(plain_times), median(ratios));
    return 0;
}

/// The boxes of `changes` whose id has parity `parity`: the changes of one layer.
struct LayerChanges {
    std::vector<BoxId> removed, updated, inserted;
    std::vector<smb::Box3d> updated_boxes, inserted_boxes;

    LayerChanges(const smb::workload::StepChanges<3>& changes, BoxId parity) {
        for (const BoxId id : changes.removed_ids)
            if (id % 2 == parity) removed.push_back(id);
        for (std::size_t i = 0; i < changes.updated_ids.size(); ++i) {
            if (changes.updated_ids[i] % 2 != parity) continue;
            updated.push_back(changes.updated_ids[i]);
            updated_boxes.push_back(changes.updated_boxes[i]);
        }
        for (std::size_t i = 0; i < changes.inserted_ids.size(); ++i) {
            if (changes.inserted_ids[i] % 2 != parity) continue;
            inserted.push_back(changes.inserted_ids[i]);
            inserted_boxes.push_back(changes.inserted_boxes[i]);
        }
    }
    void apply(World& world) const {
        if (!removed.empty()) world.remove(removed);
        if (!updated.empty()) world.update(updated, updated_boxes);
        if (!inserted.empty()) world.insert(inserted, inserted_boxes);
    }
};

void set_layers(World& world, std::span<const BoxId> ids) {
    std::vector<smb::Filter> filters(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) filters[i] = ids[i] % 2 == 0 ? smb::Filter{1, 1} : smb::Filter{2, 2};
    world.set_filter(ids, filters);
}

/// The layers scene in lockstep (--layers).
int run_layers_paired(std::size_t moving, int steps) {
    Env env(params(2 * moving, 3));
    World unfiltered;
    World layers;
    World separate[2];
    std::vector<smb::Pair> pairs;
    std::vector<double> times[3], cpu[3], to_separate, to_unfiltered, cpu_to_separate, cpu_to_unfiltered;
    std::size_t counts[3] = {0, 0, 0};
    for (int s = -1; s < steps; ++s) {
        const bool first = s < 0;
        const auto& changes = first ? env.changes() : env.step();
        const LayerChanges layer_changes[2] = {LayerChanges(changes, 0), LayerChanges(changes, 1)};
        double t[3] = {0, 0, 0};
        double c[3] = {0, 0, 0};
        for (int turn = 0; turn < 3; ++turn) {
            const int scene = (turn + (s + 3)) % 3;
            const double cpu_start = thread_seconds();
            const auto start = Clock::now();
            if (scene == 0) {
                pairs.clear();
                smb::workload::apply_changes(changes, unfiltered);
                unfiltered.detect(pairs);
                counts[0] = pairs.size();
            } else if (scene == 1) {
                pairs.clear();
                smb::workload::apply_changes(changes, layers);
                set_layers(layers, changes.inserted_ids);
                layers.detect(pairs);
                counts[1] = pairs.size();
            } else {
                counts[2] = 0;
                for (int l = 0; l < 2; ++l) {
                    pairs.clear();
                    layer_changes[l].apply(separate[l]);
                    separate[l].detect(pairs);
                    counts[2] += pairs.size();
                }
            }
            t[scene] = since(start);
            c[scene] = thread_seconds() - cpu_start;
        }
        if (first) continue;
        for (int k = 0; k < 3; ++k) {
            times[k].push_back(t[k]);
            cpu[k].push_back(c[k]);
        }
        to_separate.push_back(t[1] / t[2]);
        to_unfiltered.push_back(t[1] / t[0]);
        cpu_to_separate.push_back(c[1] / c[2]);
        cpu_to_unfiltered.push_back(c[1] / c[0]);
    }
    std::printf(
        "layers, %zu boxes, %d steps, rotating order: unfiltered %.2f ms (%zu pairs), two layers filtered %.2f ms"
        " (%zu pairs), each layer in its own world %.2f ms (%zu pairs); layers / separate: ratio of medians %.2f,"
        " median of per-step ratios %.2f; layers / unfiltered: %.2f, %.2f\n",
        2 * moving, steps, median(times[0]) * 1e3, counts[0], median(times[1]) * 1e3, counts[1], median(times[2]) * 1e3,
        counts[2], median(times[1]) / median(times[2]), median(to_separate), median(times[1]) / median(times[0]),
        median(to_unfiltered));
    std::printf(
        "  thread CPU: unfiltered %.2f ms, two layers filtered %.2f ms, each layer in its own world %.2f ms;"
        " layers / separate: %.2f, %.2f; layers / unfiltered: %.2f, %.2f\n",
        median(cpu[0]) * 1e3, median(cpu[1]) * 1e3, median(cpu[2]) * 1e3, median(cpu[1]) / median(cpu[2]),
        median(cpu_to_separate), median(cpu[1]) / median(cpu[0]), median(cpu_to_unfiltered));
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t moving = 100000;
    std::size_t statics = 1000000;
    bool paired = false;
    bool terrain = false;
    bool layers_paired = false;
    int steps = 10;
    for (int i = 1; i < argc; ++i) {
        const bool value = i + 1 < argc;
        if (std::strcmp(argv[i], "--paired") == 0) paired = true;
        if (std::strcmp(argv[i], "--terrain") == 0) terrain = true;
        if (std::strcmp(argv[i], "--layers") == 0) layers_paired = true;
        if (value && std::strcmp(argv[i], "--moving") == 0) moving = std::strtoull(argv[++i], nullptr, 10);
        if (value && std::strcmp(argv[i], "--statics") == 0) statics = std::strtoull(argv[++i], nullptr, 10);
        if (value && std::strcmp(argv[i], "--steps") == 0) steps = std::atoi(argv[++i]);
    }
    if (paired) return run_paired(moving, statics, steps, terrain);
    if (layers_paired) return run_layers_paired(moving, steps);
    auto nothing = [](std::span<const BoxId>) {};
    std::printf("moving %zu, statics %zu, steps %d (World<double, 3>; times in ms; first = load + detect)\n\n", moving,
                statics, steps);
    std::printf("| %-28s | %9s | %9s | %9s | %9s | %9s | %7s | %9s | %9s |\n", "scene", "boxes", "pairs", "first",
                "step", "update", "MiB", "refreshed", "cached");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");

    // The moving boxes alone: the default detection, and the filtered path with filters that
    // pass everything.
    {
        Env env(params(moving, 1));
        World world;
        print("plain (default detection)", run(env, world, steps, nothing));
    }
    {
        Env env(params(moving, 1));
        World world;
        auto all_pass = [&](std::span<const BoxId> ids) {
            world.set_filter(ids, std::vector<smb::Filter>(ids.size(), smb::Filter{3, ~0u}));
        };
        print("all-pass filters", run(env, world, steps, all_pass));
    }

    // The same moving boxes in the middle of a second, static placement.
    {
        Env env(params(moving, 1));
        World world;
        const double inserted = insert_statics(env, statics, world);
        std::printf("| %-28s | %9zu | %9s | %9.1f | %9s | %9s | %7s | %9s | %9s |\n", "(statics inserted)", statics, "",
                    inserted * 1e3, "", "", "", "", "");
        print("moving + statics", run(env, world, steps, nothing));
    }

    // Two layers that ignore each other, against the same boxes unfiltered and one layer alone.
    {
        Env env(params(2 * moving, 3));
        World world;
        print("two layers, no filters", run(env, world, steps, nothing));
    }
    {
        Env env(params(2 * moving, 3));
        World world;
        auto layers = [&](std::span<const BoxId> ids) {
            std::vector<smb::Filter> filters(ids.size());
            for (std::size_t i = 0; i < ids.size(); ++i)
                filters[i] = ids[i] % 2 == 0 ? smb::Filter{1, 1} : smb::Filter{2, 2};
            world.set_filter(ids, filters);
        };
        print("two layers, filtered", run(env, world, steps, layers));
    }
    {
        // One layer alone: the other layer's boxes pair with nothing (mask 0).
        Env env(params(2 * moving, 3));
        World world;
        auto one_layer = [&](std::span<const BoxId> ids) {
            std::vector<smb::Filter> filters(ids.size());
            for (std::size_t i = 0; i < ids.size(); ++i)
                filters[i] = ids[i] % 2 == 0 ? smb::Filter{1, 1} : smb::Filter{2, 0};
            world.set_filter(ids, filters);
        };
        print("one layer + one of mask 0", run(env, world, steps, one_layer));
    }
    return 0;
}
