// SPDX-License-Identifier: MIT
// smb_compare: runs ONE broad-phase method on ONE scene and prints one JSON line with its
// timings, peak memory and a digest of every step's pair set. One process per method and
// scene keeps each peak memory its own; scripts/bench-compare.py runs the whole matrix.

#include <malloc.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "heap_meter.hpp"
#include "pair_digest.hpp"
#include "peers/peer.hpp"
#include "scenes/scene.hpp"

namespace smb::bench {
namespace {

struct RunOptions {
    std::string method;
    SceneSpec scene;
    std::size_t steps = 10;
    std::size_t early_steps = 10;
    bool check_overlaps = true;
};

constexpr const char* usage_text =
    "usage: smb_compare --method NAME --scene FAMILY --dim 2|3 --boxes N --lambda L\n"
    "                   [--steps S] [--seed K] [--early-steps E] [--no-check]\n"
    "       smb_compare --list\n"
    "Runs one method on one scene (step 0 plus S steps) and prints a JSON line.\n"
    "FAMILY: paper, sparse (3D), clustered, mixed, loguniform2, loguniform3 (sizes log-uniform over\n"
    "two or three decades up to 1), islands (dense clusters in empty space), plane (boxes on a\n"
    "plane), rods (one side 10-50 times the others). METHOD 'none' runs the scene alone\n"
    "(the harness's own memory). --no-check skips the untimed exact-overlap check.\n"
    "Times: first_step_s (the build), early_median_s (median of steps 1..E after it, E = 10 by\n"
    "default), steady_median_s (median of the steps after those; 0 when S <= E), median_step_s\n"
    "(median of all S steps after the build) and step_s (every step after the build); the\n"
    "same in CPU seconds of the process, all threads (*_cpu_s).\n";

std::size_t peak_rss_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

std::size_t resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t total_pages = 0, resident_pages = 0;
    statm >> total_pages >> resident_pages;
    return resident_pages * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

// Peak resident bytes since the last reset_resident_peak(), from VmHWM (Linux).
std::size_t resident_peak_bytes() {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == "VmHWM:") {
            std::size_t kib = 0;
            status >> kib;
            return kib * 1024;
        }
        status.ignore(1 << 12, '\n');
    }
    return peak_rss_bytes();
}

// Writing 5 to clear_refs resets VmHWM to the current resident size (Linux 4.0+), so that
// the peak of the method's own run is not hidden by freed memory of the scene's set-up.
void reset_resident_peak() {
    malloc_trim(0);
    std::ofstream clear_refs("/proc/self/clear_refs");
    clear_refs << "5" << std::endl;
}

// CPU seconds of the whole process (all its threads): on a machine shared with other work it
// shows what a single-threaded method costs without the time it waited for a core.
double process_cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double median_of(std::vector<double> values) {
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// Untimed: every reported pair must be an exact closed overlap of the step's boxes.
template <int Dim>
void check_exact(const SceneStep<Dim>& step, const std::vector<Pair>& pairs,
                 std::vector<std::uint32_t>& position_of_id) {
    BoxId largest = 0;
    for (BoxId id : step.ids) largest = std::max(largest, id);
    position_of_id.assign(largest + 1, ~std::uint32_t{0});
    for (std::size_t i = 0; i < step.size(); ++i) position_of_id[step.ids[i]] = static_cast<std::uint32_t>(i);
    for (const Pair& pair : pairs) {
        if (pair.b > largest || position_of_id[pair.a] == ~std::uint32_t{0} ||
            position_of_id[pair.b] == ~std::uint32_t{0})
            throw std::logic_error("pair names a box that is not in the step");
        if (!overlaps(step.boxes[position_of_id[pair.a]], step.boxes[position_of_id[pair.b]]))
            throw std::logic_error("pair of boxes that do not overlap");
    }
}

template <int Dim>
int run(const RunOptions& options) {
    using Clock = std::chrono::steady_clock;
    auto scene = make_scene<Dim>(options.scene);
    std::unique_ptr<Peer<Dim>> peer;
    if (options.method != "none") {
        peer = make_peer<Dim>(options.method);
        if (!peer) {
            std::cerr << "method '" << options.method << "' is not available in " << Dim << "D in this build\n";
            return 2;
        }
    }

    std::vector<Pair> pairs;
    std::vector<std::uint32_t> position_of_id;
    std::vector<double> step_seconds, step_cpu_seconds;
    std::vector<std::uint64_t> digests;
    std::vector<std::size_t> pair_counts;
    double first_seconds = 0, first_cpu_seconds = 0;
    std::size_t first_boxes = 0, most_boxes = 0, pair_capacity = 0, resident_before = 0;
    bool pair_list_grew = false;  // then the method's heap count includes the pair list

    for (std::size_t index = 0; index <= options.steps; ++index) {
        const SceneStep<Dim>& step = scene->advance();
        most_boxes = std::max(most_boxes, step.size());
        if (index == 0) {
            first_boxes = step.size();
            reset_resident_peak();
            resident_before = resident_bytes();
        }
        // The pair list belongs to the harness: grown here, outside the method's timing and
        // heap count, to twice the last step's pairs (step 0: four per box).
        const std::size_t wanted = index == 0 ? 4 * step.size() + 1024 : 2 * pairs.size() + 1024;
        if (pairs.capacity() < wanted) {
            // Written once here, so that the kernel maps its pages before the timing: reserve()
            // alone leaves the first write of each page to the method, a fault that costs more
            // than the write (12 us a page on a virtual machine here).
            pairs.reserve(wanted);
            pairs.resize(pairs.capacity());
            pairs.clear();
        }
        const std::size_t capacity_before = pairs.capacity();
        if (peer) peer->prepare(step);
        const double cpu_start = process_cpu_seconds();
        const auto start = Clock::now();
        if (peer) {
            const heap_meter::CountingScope count_method_heap;
            if (index == 0)
                peer->build(step, pairs);
            else
                peer->step(step, pairs);
        }
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        const double cpu_seconds = process_cpu_seconds() - cpu_start;
        if (pairs.capacity() != capacity_before) pair_list_grew = true;
        if (index == 0) {
            first_seconds = seconds;
            first_cpu_seconds = cpu_seconds;
        } else {
            step_seconds.push_back(seconds);
            step_cpu_seconds.push_back(cpu_seconds);
        }
        pair_capacity = std::max(pair_capacity, pairs.capacity());
        if (options.check_overlaps) check_exact(step, pairs, position_of_id);
        pair_counts.push_back(pairs.size());
        digests.push_back(digest_pairs(pairs));
    }

    // The steps right after the build apart from the later ones: a method may still be settling
    // in them (smb's lists are sorted from scratch by the build, a tree's shape is young).
    const auto early_count = static_cast<std::ptrdiff_t>(std::min(options.early_steps, step_seconds.size()));
    const std::vector<double> early(step_seconds.begin(), step_seconds.begin() + early_count);
    const std::vector<double> steady(step_seconds.begin() + early_count, step_seconds.end());
    const std::vector<double> early_cpu(step_cpu_seconds.begin(), step_cpu_seconds.begin() + early_count);
    const std::vector<double> steady_cpu(step_cpu_seconds.begin() + early_count, step_cpu_seconds.end());

    std::ostringstream json;
    json << "{\"method\":\"" << options.method << "\",\"family\":\"" << options.scene.family << "\",\"dim\":" << Dim
         << ",\"boxes\":" << options.scene.boxes << ",\"lambda\":" << options.scene.update_factor
         << ",\"seed\":" << options.scene.seed << ",\"steps\":" << options.steps << ",\"first_boxes\":" << first_boxes
         << ",\"max_boxes\":" << most_boxes << ",\"first_step_s\":" << first_seconds
         << ",\"median_step_s\":" << median_of(step_seconds) << ",\"early_steps\":" << early.size()
         << ",\"early_median_s\":" << median_of(early) << ",\"steady_median_s\":" << median_of(steady)
         << ",\"first_step_cpu_s\":" << first_cpu_seconds << ",\"early_median_cpu_s\":" << median_of(early_cpu)
         << ",\"steady_median_cpu_s\":" << median_of(steady_cpu) << ",\"min_step_s\":"
         << (step_seconds.empty() ? 0.0 : *std::min_element(step_seconds.begin(), step_seconds.end()))
         << ",\"peak_rss_bytes\":" << peak_rss_bytes() << ",\"resident_before_bytes\":" << resident_before
         << ",\"resident_peak_bytes\":" << resident_peak_bytes()
         << ",\"heap_meter\":" << (heap_meter::available() ? "true" : "false")
         << ",\"heap_peak_bytes\":" << heap_meter::peak_bytes() << ",\"heap_live_bytes\":" << heap_meter::live_bytes()
         << ",\"pair_list_grew\":" << (pair_list_grew ? "true" : "false")
         << ",\"pair_list_bytes\":" << pair_capacity * sizeof(Pair) << ",\"step_s\":[";
    for (std::size_t i = 0; i < step_seconds.size(); ++i) json << (i ? "," : "") << step_seconds[i];
    json << "],\"pairs\":[";
    for (std::size_t i = 0; i < pair_counts.size(); ++i) json << (i ? "," : "") << pair_counts[i];
    json << "],\"digests\":[";
    for (std::size_t i = 0; i < digests.size(); ++i) {
        char hex[20];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(digests[i]));
        json << (i ? "," : "") << '"' << hex << '"';
    }
    json << "]";
    if (peer) {
        const std::string details = peer->details_json();
        if (!details.empty()) json << ',' << details;
    }
    json << "}";
    std::cout << json.str() << std::endl;
    // Tearing down a million proxies one by one (Bullet's sweep removes each in O(N)) would
    // only slow the harness; the process ends here and the OS takes the memory back.
    std::fflush(nullptr);
    std::_Exit(0);
}

int list_methods() {
    for (const PeerInfo& info : available_peers())
        std::cout << info.name << ',' << (info.runs_2d ? "2d" : "") << (info.runs_2d && info.runs_3d ? "+" : "")
                  << (info.runs_3d ? "3d" : "") << '\n';
    return 0;
}

int main_with_arguments(int argc, char** argv) {
    RunOptions options;
    std::map<std::string, std::string> values;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--list") return list_methods();
        if (flag == "--help" || flag == "-h") {
            std::cout << usage_text;
            return 0;
        }
        if (flag == "--no-check") {
            options.check_overlaps = false;
            continue;
        }
        if (flag.rfind("--", 0) != 0 || i + 1 >= argc) {
            std::cerr << "bad argument '" << flag << "'\n" << usage_text;
            return 2;
        }
        values[flag.substr(2)] = argv[++i];
    }
    for (const auto& [key, value] : values) {
        if (key == "method")
            options.method = value;
        else if (key == "scene")
            options.scene.family = value;
        else if (key == "dim")
            options.scene.dimension = std::stoi(value);
        else if (key == "boxes")
            options.scene.boxes = std::stoull(value);
        else if (key == "lambda")
            options.scene.update_factor = std::stod(value);
        else if (key == "seed")
            options.scene.seed = std::stoull(value);
        else if (key == "steps")
            options.steps = std::stoull(value);
        else if (key == "early-steps")
            options.early_steps = std::stoull(value);
        else {
            std::cerr << "unknown option --" << key << '\n' << usage_text;
            return 2;
        }
    }
    if (options.method.empty()) {
        std::cerr << usage_text;
        return 2;
    }
    if (options.scene.dimension == 2) return run<2>(options);
    if (options.scene.dimension == 3) return run<3>(options);
    std::cerr << "--dim must be 2 or 3\n";
    return 2;
}

}  // namespace
}  // namespace smb::bench

int main(int argc, char** argv) {
    try {
        return smb::bench::main_with_arguments(argc, argv);
    } catch (const std::exception& error) {
        std::cerr << "smb_compare: " << error.what() << '\n';
        return 1;
    }
}
