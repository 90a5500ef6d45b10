// SPDX-License-Identifier: MIT
// A periodic domain beside the same scene without one, on the paper's environment (workload/):
// 3D, density 0.4, size ratio 2.5, Λ = 1e-3, double boxes. The domain is the environment's cube
// [0, x) on every axis, so the boxes within their extent of a far face get images and the pairs
// across the faces are found too. Every step, each method detects the same boxes (in an order
// that alternates from step to step, so that neither always runs second on a warm cache); the
// first step (the build) is timed apart from the median of the steady ones.
//   detector     Detector<double, 3> over the scene's array (kept by swap-remove, as a
//                simulation keeps its bodies), detect(boxes, pairs) against
//                detect(boxes, domain, periodic_pairs)
//   world        World<double, 3> following the scene's changes, detect(pairs) against
//                detect(domain, periodic_pairs); the update calls are not timed
// Usage: smb_periodic_compare [--boxes N] [--steps S] [--threads T] [--seed K]

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "smb/smb.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/swap_remove_mirror.hpp"
#include "smb/workload/world_sync.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using Env = smb::workload::DynamicEnvironment<3>;

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

struct Options {
    std::size_t boxes = 1000000;
    int steps = 20;
    std::size_t threads = 1;
    std::uint64_t seed = 1;
};

struct Series {
    double first = 0;
    std::vector<double> steady;
    std::size_t pairs = 0;
};

void print(const char* method, const char* variant, const Series& s, const Series& base) {
    const double m = median(s.steady);
    std::printf("%-9s %-9s first %9.1f ms   steady median %8.2f ms   min %8.2f ms   pairs %9zu   ratio %5.2f\n", method,
                variant, 1e3 * s.first, 1e3 * m, 1e3 * *std::min_element(s.steady.begin(), s.steady.end()), s.pairs,
                m / median(base.steady));
}

smb::workload::EnvironmentParams params(const Options& o) {
    smb::workload::EnvironmentParams p;
    p.box_count = o.boxes;
    p.packing_density = 0.4;
    p.size_ratio = 2.5;
    p.update_factor = 1e-3;
    p.seed = o.seed;
    return p;
}

smb::PeriodicDomain3d cube(double side) {
    smb::PeriodicDomain3d domain;
    for (int k = 0; k < 3; ++k) domain.wrap(k, 0.0, side);
    return domain;
}

/// Runs `plain` and `periodic` (callables timing one detection each) over the steps.
template <class Step, class Plain, class Periodic>
void compare(const char* method, const Options& o, Step&& step, Plain&& plain, Periodic&& periodic) {
    Series a;
    Series b;
    a.first = plain(a.pairs);
    b.first = periodic(b.pairs);
    for (int s = 0; s < o.steps; ++s) {
        step();
        if (s % 2 == 0) {
            a.steady.push_back(plain(a.pairs));
            b.steady.push_back(periodic(b.pairs));
        } else {
            b.steady.push_back(periodic(b.pairs));
            a.steady.push_back(plain(a.pairs));
        }
    }
    print(method, "plain", a, a);
    print(method, "periodic", b, a);
}

void run_detector(const Options& o) {
    Env env(params(o));
    smb::workload::SwapRemoveMirror<smb::Box3d> mirror;
    mirror.follow(env.changes().removed_ids, env.changes().inserted_ids, env.ids(), env.boxes());
    const auto domain = cube(env.cube_side());
    smb::DetectorSettings settings;
    settings.threads = o.threads;
    smb::Detector3d plain_detector(settings);
    smb::Detector3d periodic_detector(settings);
    std::vector<smb::Pair> pairs;
    std::vector<smb::PeriodicPair> periodic_pairs;
    compare(
        "detector", o,
        [&] {
            env.step();
            mirror.follow(env.changes().removed_ids, env.changes().inserted_ids, env.ids(), env.boxes());
        },
        [&](std::size_t& count) {
            pairs.clear();
            const auto start = Clock::now();
            plain_detector.detect(mirror.boxes(), pairs);
            const double t = since(start);
            count = pairs.size();
            return t;
        },
        [&](std::size_t& count) {
            periodic_pairs.clear();
            const auto start = Clock::now();
            periodic_detector.detect(mirror.boxes(), domain, periodic_pairs);
            const double t = since(start);
            count = periodic_pairs.size();
            return t;
        });
}

void run_world(const Options& o) {
    Env env(params(o));
    const auto domain = cube(env.cube_side());
    smb::WorldSettings settings;
    settings.threads = o.threads;
    smb::World3d plain_world(settings);
    smb::World3d periodic_world(settings);
    smb::workload::apply_changes(env.changes(), plain_world);
    smb::workload::apply_changes(env.changes(), periodic_world);
    std::vector<smb::Pair> pairs;
    std::vector<smb::PeriodicPair> periodic_pairs;
    compare(
        "world", o,
        [&] {
            const auto& changes = env.step();
            smb::workload::apply_changes(changes, plain_world);
            smb::workload::apply_changes(changes, periodic_world);
        },
        [&](std::size_t& count) {
            pairs.clear();
            const auto start = Clock::now();
            plain_world.detect(pairs);
            const double t = since(start);
            count = pairs.size();
            return t;
        },
        [&](std::size_t& count) {
            periodic_pairs.clear();
            const auto start = Clock::now();
            periodic_world.detect(domain, periodic_pairs);
            const double t = since(start);
            count = periodic_pairs.size();
            return t;
        });
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string name = argv[i];
        const char* value = argv[i + 1];
        if (name == "--boxes") {
            o.boxes = std::strtoull(value, nullptr, 10);
        } else if (name == "--steps") {
            o.steps = std::atoi(value);
        } else if (name == "--threads") {
            o.threads = std::strtoull(value, nullptr, 10);
        } else if (name == "--seed") {
            o.seed = std::strtoull(value, nullptr, 10);
        } else {
            std::fprintf(stderr, "usage: smb_periodic_compare [--boxes N] [--steps S] [--threads T] [--seed K]\n");
            return 64;
        }
    }
    if (o.steps < 1) o.steps = 1;
    std::printf(
        "periodic beside plain: 3D paper environment, N %zu, E 0.4, H 2.5, update factor 0.001, %d steps, "
        "%zu thread(s), seed %llu\n",
        o.boxes, o.steps, o.threads, static_cast<unsigned long long>(o.seed));
    run_detector(o);
    run_world(o);
    return 0;
}
