// SPDX-License-Identifier: MIT
// smb_bench_events: what pair events add to a detection, on the paper's dynamic environment.
// Two worlds (or, with --detector, two detectors over one array kept by swap-remove) follow the
// same scene; every step one detects alone and the other detects and updates its PairEvents,
// in alternating order so that neither always runs on a warmer cache. Prints the median step of
// each after the build, the median time of the events' update alone (the same work, timed
// apart on a twin PairEvents) and the events per step, in wall-clock and in the thread's CPU
// time. --check compares every step's events, outside the timings, with the set differences
// of the sorted pair lists (by ids, for the detector: swap-removes included).
//
//   smb_bench_events [-n N] [--steps S] [--update-factor L] [--dim 2|3] [--threads T]
//                    [--seed K] [--detector] [--check]

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <string>
#include <vector>

#include "smb/detector.hpp"
#include "smb/pair_events.hpp"
#include "smb/workload/dynamic_environment.hpp"
#include "smb/workload/swap_remove_mirror.hpp"
#include "smb/workload/world_sync.hpp"
#include "smb/world.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Options {
    std::size_t boxes = 1000000;
    std::size_t steps = 20;
    double update_factor = 1e-3;
    int dim = 3;
    unsigned threads = 1;
    std::uint64_t seed = 1;
    bool detector = false;
    bool check = false;
};

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// CPU time of the calling thread: on a machine shared with other work it leaves out the time
/// the thread waited for a core, which the wall-clock times include.
double thread_cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

/// Wall and CPU seconds of one call.
struct Timed {
    double wall = 0;
    double cpu = 0;
};
template <class Call>
Timed timed(Call&& call) {
    const double cpu = thread_cpu_seconds();
    const auto start = Clock::now();
    call();
    return {seconds_since(start), thread_cpu_seconds() - cpu};
}

struct Series {
    std::vector<double> alone_wall, alone_cpu, events_wall, events_cpu, update_wall, update_cpu, events, pairs;
};

/// The pairs named by ids, sorted.
std::vector<smb::Pair> by_ids(std::span<const smb::Pair> pairs, std::span<const smb::BoxId> ids) {
    std::vector<smb::Pair> out;
    out.reserve(pairs.size());
    for (const smb::Pair& pair : pairs) {
        const smb::BoxId a = ids[pair.a];
        const smb::BoxId b = ids[pair.b];
        out.push_back(a < b ? smb::Pair{a, b} : smb::Pair{b, a});
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<smb::Pair> difference(const std::vector<smb::Pair>& x, const std::vector<smb::Pair>& y) {
    std::vector<smb::Pair> out;
    std::set_difference(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(out));
    return out;
}

/// Whether the events equal the set differences of the two lists (all named by ids, sorted).
bool events_agree(const std::vector<smb::Pair>& begun, const std::vector<smb::Pair>& ended,
                  const std::vector<smb::Pair>& before, const std::vector<smb::Pair>& now) {
    return begun == difference(now, before) && ended == difference(before, now);
}

template <int Dim>
int run(const Options& options) {
    smb::workload::EnvironmentParams params;
    params.box_count = options.boxes;
    params.update_factor = options.update_factor;
    params.seed = options.seed;
    smb::workload::DynamicEnvironment<Dim> environment(params);
    smb::WorldSettings settings;
    settings.threads = options.threads;
    smb::World<double, Dim> world_alone(settings);
    smb::World<double, Dim> world_events(settings);
    smb::Detector<double, Dim> detector_alone(smb::DetectorSettings{settings, 0});
    smb::Detector<double, Dim> detector_events(smb::DetectorSettings{settings, 0});
    smb::workload::SwapRemoveMirror<smb::Box<double, Dim>> mirror;
    smb::PairEvents events(options.threads);
    smb::PairEvents twin(options.threads);
    std::vector<smb::Pair> pairs_alone;
    std::vector<smb::Pair> pairs_events;
    std::vector<smb::Pair> before;  // the last step's pairs by ids, for --check
    std::vector<smb::BoxId> ids_before;
    Series series;
    bool agreed = true;

    for (std::size_t step = 0; step <= options.steps; ++step) {
        if (step > 0) environment.step();
        const auto& changes = environment.changes();
        if (options.detector) {
            mirror.follow(changes.removed_ids, changes.inserted_ids, environment.ids(), environment.boxes());
        } else {
            smb::workload::apply_changes(changes, world_alone);
            smb::workload::apply_changes(changes, world_events);
        }
        const auto detect_alone = [&] {
            pairs_alone.clear();
            if (options.detector) {
                detector_alone.detect(mirror.boxes(), pairs_alone);
            } else {
                world_alone.detect(pairs_alone);
            }
        };
        const auto detect_events = [&] {
            pairs_events.clear();
            if (options.detector) {
                // The caller's share of the events: telling them of its swap-removes.
                for (const auto& [removed, last] : mirror.swaps()) events.swap_remove(removed, last);
                detector_events.detect(mirror.boxes(), pairs_events, events);
            } else {
                world_events.detect(pairs_events, events);
            }
        };
        Timed alone;
        Timed with_events;
        if (step % 2 == 0) {
            alone = timed(detect_alone);
            with_events = timed(detect_events);
        } else {
            with_events = timed(detect_events);
            alone = timed(detect_alone);
        }
        const Timed update = timed([&] {
            if (options.detector) {
                for (const auto& [removed, last] : mirror.swaps()) twin.swap_remove(removed, last);
            }
            twin.update(pairs_alone);
        });
        if (pairs_alone.size() != pairs_events.size()) {
            std::fprintf(stderr, "step %zu: %zu pairs alone, %zu with events\n", step, pairs_alone.size(),
                         pairs_events.size());
            return 1;
        }
        if (options.check) {
            std::vector<smb::BoxId> ids_now;
            if (options.detector) ids_now.assign(mirror.ids().begin(), mirror.ids().end());
            // A detector's pairs are named by ids through the array's ids at their detection;
            // a world's are ids already.
            const auto named = [&](std::span<const smb::Pair> pairs, const std::vector<smb::BoxId>& ids) {
                if (options.detector) return by_ids(pairs, ids);
                std::vector<smb::Pair> sorted(pairs.begin(), pairs.end());
                std::sort(sorted.begin(), sorted.end());
                return sorted;
            };
            const std::vector<smb::Pair> now = named(pairs_events, ids_now);
            if (!events_agree(named(events.begun(), ids_now), named(events.ended(), ids_before), before, now)) {
                std::fprintf(stderr, "step %zu: the events differ from the set differences\n", step);
                agreed = false;
            }
            before = now;
            ids_before = ids_now;
        }
        if (step == 0) continue;  // the build
        series.alone_wall.push_back(alone.wall);
        series.alone_cpu.push_back(alone.cpu);
        series.events_wall.push_back(with_events.wall);
        series.events_cpu.push_back(with_events.cpu);
        series.update_wall.push_back(update.wall);
        series.update_cpu.push_back(update.cpu);
        series.events.push_back(static_cast<double>(events.begun().size() + events.ended().size()));
        series.pairs.push_back(static_cast<double>(pairs_events.size()));
    }

    const double a = median(series.alone_wall);
    const double b = median(series.events_wall);
    const double ac = median(series.alone_cpu);
    const double bc = median(series.events_cpu);
    const double uc = median(series.update_cpu);
    std::printf("%dD, %zu boxes, update factor %g, %zu steps after the build, %u thread(s), seed %llu, %s\n", Dim,
                options.boxes, options.update_factor, options.steps, options.threads,
                static_cast<unsigned long long>(options.seed),
                options.detector ? "Detector (array kept by swap-remove)" : "World");
    std::printf("  pairs per step       median %.0f\n", median(series.pairs));
    std::printf("  events per step      median %.0f (begun + ended)\n", median(series.events));
    std::printf(
        "  wall (median)        detect alone %.3f ms, detect + events %.3f ms (%+.1f%%), events update "
        "alone %.3f ms (%.1f%%)\n",
        1e3 * a, 1e3 * b, 100.0 * (b - a) / a, 1e3 * median(series.update_wall),
        100.0 * median(series.update_wall) / a);
    std::printf(
        "  CPU (median)         detect alone %.3f ms, detect + events %.3f ms (%+.1f%%), events update "
        "alone %.3f ms (%.1f%%)\n",
        1e3 * ac, 1e3 * bc, 100.0 * (bc - ac) / ac, 1e3 * uc, 100.0 * uc / ac);
    std::printf("  events held          %.1f bytes per pair\n",
                static_cast<double>(events.bytes_held()) / std::max<double>(1, median(series.pairs)));
    if (options.check) std::printf("  check                %s\n", agreed ? "OK, every step" : "FAILED");
    return agreed ? 0 : 1;
}

bool parse(int argc, char** argv, Options& options) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--detector") {
            options.detector = true;
            continue;
        }
        if (arg == "--check") {
            options.check = true;
            continue;
        }
        if (i + 1 >= argc) return false;
        const char* value = argv[++i];
        if (arg == "-n") {
            options.boxes = std::strtoull(value, nullptr, 10);
        } else if (arg == "--steps") {
            options.steps = std::strtoull(value, nullptr, 10);
        } else if (arg == "--update-factor") {
            options.update_factor = std::strtod(value, nullptr);
        } else if (arg == "--dim") {
            options.dim = std::atoi(value);
        } else if (arg == "--threads") {
            options.threads = static_cast<unsigned>(std::strtoul(value, nullptr, 10));
        } else if (arg == "--seed") {
            options.seed = std::strtoull(value, nullptr, 10);
        } else {
            return false;
        }
    }
    return (options.dim == 2 || options.dim == 3) && options.steps > 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    if (!parse(argc, argv, options)) {
        std::fprintf(stderr,
                     "usage: smb_bench_events [-n N] [--steps S] [--update-factor L] [--dim 2|3] [--threads T] "
                     "[--seed K] [--detector] [--check]\n");
        return 2;
    }
    return options.dim == 2 ? run<2>(options) : run<3>(options);
}
