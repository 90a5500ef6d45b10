// SPDX-License-Identifier: MIT
// smb_bench_events: what pair events add to a detection, on the paper's dynamic environment.
// Two worlds follow the same scene; every step one detects alone and the other detects and
// updates its PairEvents, in alternating order so that neither always runs on a warmer cache.
// Prints the median step of each after the build, the median time of the events' update
// (the same work, timed apart on a twin PairEvents) and the events per step, in wall-clock
// and in the thread's CPU time.
//
//   smb_bench_events [-n N] [--steps S] [--update-factor L] [--dim 2|3] [--threads T] [--seed K]

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "smb/pair_events.hpp"
#include "smb/workload/dynamic_environment.hpp"
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

template <int Dim>
int run(const Options& options) {
    smb::workload::EnvironmentParams params;
    params.box_count = options.boxes;
    params.update_factor = options.update_factor;
    params.seed = options.seed;
    smb::workload::DynamicEnvironment<Dim> environment(params);
    smb::WorldSettings settings;
    settings.threads = options.threads;
    smb::World<double, Dim> alone(settings);
    smb::World<double, Dim> with_events(settings);
    smb::PairEvents events;
    smb::PairEvents twin;
    std::vector<smb::Pair> pairs_alone;
    std::vector<smb::Pair> pairs_events;
    std::vector<double> detect_alone;
    std::vector<double> detect_with_events;
    std::vector<double> events_only;
    std::vector<double> alone_cpus;
    std::vector<double> events_cpus;
    std::vector<double> events_only_cpus;
    std::vector<double> event_counts;
    std::vector<double> pair_counts;

    for (std::size_t step = 0; step <= options.steps; ++step) {
        if (step > 0) environment.step();
        smb::workload::apply_changes(environment.changes(), alone);
        smb::workload::apply_changes(environment.changes(), with_events);
        double alone_seconds = 0;
        double events_seconds = 0;
        double alone_cpu = 0;
        double events_cpu = 0;
        auto time_alone = [&] {
            pairs_alone.clear();
            const double cpu = thread_cpu_seconds();
            const auto start = Clock::now();
            alone.detect(pairs_alone);
            alone_seconds = seconds_since(start);
            alone_cpu = thread_cpu_seconds() - cpu;
        };
        auto time_events = [&] {
            pairs_events.clear();
            const double cpu = thread_cpu_seconds();
            const auto start = Clock::now();
            with_events.detect(pairs_events, events);
            events_seconds = seconds_since(start);
            events_cpu = thread_cpu_seconds() - cpu;
        };
        if (step % 2 == 0) {
            time_alone();
            time_events();
        } else {
            time_events();
            time_alone();
        }
        // The events' own share, timed apart: a twin that follows the pairs of the world alone.
        const double twin_cpu = thread_cpu_seconds();
        const auto twin_start = Clock::now();
        twin.update(pairs_alone);
        const double twin_seconds = seconds_since(twin_start);
        const double twin_cpu_seconds = thread_cpu_seconds() - twin_cpu;
        if (pairs_alone.size() != pairs_events.size()) {
            std::fprintf(stderr, "step %zu: %zu pairs alone, %zu with events\n", step, pairs_alone.size(),
                         pairs_events.size());
            return 1;
        }
        if (step == 0) continue;  // the build
        detect_alone.push_back(alone_seconds);
        detect_with_events.push_back(events_seconds);
        events_only.push_back(twin_seconds);
        alone_cpus.push_back(alone_cpu);
        events_cpus.push_back(events_cpu);
        events_only_cpus.push_back(twin_cpu_seconds);
        event_counts.push_back(static_cast<double>(events.begun().size() + events.ended().size()));
        pair_counts.push_back(static_cast<double>(pairs_events.size()));
    }
    const double a = median(detect_alone);
    const double b = median(detect_with_events);
    std::printf("%dD, %zu boxes, update factor %g, %zu steps after the build, %u thread(s), seed %llu\n", Dim,
                options.boxes, options.update_factor, options.steps, options.threads,
                static_cast<unsigned long long>(options.seed));
    std::printf("  pairs per step       median %.0f\n", median(pair_counts));
    std::printf("  events per step      median %.0f (begun + ended)\n", median(event_counts));
    std::printf("  detect alone         median %.3f ms (min %.3f)\n", 1e3 * a,
                1e3 * *std::min_element(detect_alone.begin(), detect_alone.end()));
    std::printf("  detect + events      median %.3f ms (min %.3f)\n", 1e3 * b,
                1e3 * *std::min_element(detect_with_events.begin(), detect_with_events.end()));
    std::printf("  events update alone  median %.3f ms (%.1f%% of the median detection)\n", 1e3 * median(events_only),
                100.0 * median(events_only) / a);
    std::printf("  overhead             %+.1f%% of the median detection\n", 100.0 * (b - a) / a);
    const double ac = median(alone_cpus);
    const double bc = median(events_cpus);
    std::printf("  CPU time (median)    detect alone %.3f ms, detect + events %.3f ms, events update alone %.3f ms\n",
                1e3 * ac, 1e3 * bc, 1e3 * median(events_only_cpus));
    std::printf("  overhead in CPU time %+.1f%% (events update alone: %.1f%%)\n", 100.0 * (bc - ac) / ac,
                100.0 * median(events_only_cpus) / ac);
    std::printf("  events held          %.1f bytes per pair\n",
                static_cast<double>(events.bytes_held()) / std::max<double>(1, median(pair_counts)));
    return 0;
}

bool parse(int argc, char** argv, Options& options) {
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
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
                     "usage: smb_bench_events [-n N] [--steps S] [--update-factor L] [--dim 2|3] "
                     "[--threads T] [--seed K]\n");
        return 2;
    }
    return options.dim == 2 ? run<2>(options) : run<3>(options);
}
