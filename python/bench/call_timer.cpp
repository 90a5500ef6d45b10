// SPDX-License-Identifier: MIT
// The C++ calls that smb.find_overlapping_pairs and smb.Detector.detect make, timed the way
// python/bench/compare_peers.py times the Python ones, on the same boxes (a raw float64 file of
// (N, 2, D) boxes), so that the binding's overhead is their ratio.
//   smb_python_call_timer BOXES_FILE DIM REPEATS [wall|cpu]
// prints one JSON object: the median and minimum seconds of each call, and the pair count.
// "cpu" times the calling thread's CPU time (Python's time.thread_time), which a shared
// machine's load disturbs less than the wall clock; the detections run on that one thread.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "smb/detector.hpp"
#include "smb/world.hpp"

namespace {

struct Timing {
    double median = 0;
    double minimum = 0;
};

bool thread_cpu_clock = false;

double now_seconds() {
    if (thread_cpu_clock) {
        timespec time{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &time);
        return static_cast<double>(time.tv_sec) + 1e-9 * static_cast<double>(time.tv_nsec);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <class Call>
Timing time_calls(int repeats, Call&& call) {
    std::vector<double> seconds;
    for (int r = 0; r < repeats; ++r) {
        const double start = now_seconds();
        call();
        seconds.push_back(now_seconds() - start);
    }
    std::sort(seconds.begin(), seconds.end());
    return {seconds[seconds.size() / 2], seconds.front()};
}

template <int Dim>
int run(const std::vector<double>& raw, int repeats) {
    using Box = smb::Box<double, Dim>;
    std::vector<Box> boxes(raw.size() / (2 * Dim));
    std::copy(raw.begin(), raw.end(), reinterpret_cast<double*>(boxes.data()));

    std::size_t found = 0;
    // As smb.find_overlapping_pairs: the one-shot detection, then the pairs sorted.
    const Timing find = time_calls(repeats, [&] {
        std::vector<smb::Pair> pairs = smb::find_overlapping_pairs(boxes);
        smb::sort_pairs(pairs);
        found = pairs.size();
    });
    // As smb.Detector.detect: one detector, called again on the same boxes.
    smb::Detector<double, Dim> detector;
    std::vector<smb::Pair> pairs;
    detector.detect(boxes, pairs);
    const Timing detect = time_calls(repeats, [&] {
        pairs.clear();
        detector.detect(boxes, pairs);
    });
    // As smb.Detector.detect hands its pairs to a new array: a new vector each call, with room
    // for the last call's pairs and an eighth more, kept until the next call.
    std::vector<smb::Pair> kept;
    const Timing fresh = time_calls(repeats, [&] {
        std::vector<smb::Pair> next;
        next.reserve(pairs.size() + pairs.size() / 8);
        detector.detect(boxes, next);
        kept = std::move(next);
    });
    std::printf(
        "{\"boxes\": %zu, \"pairs\": %zu, \"find_median\": %.6f, \"find_min\": %.6f, \"detect_median\": %.6f, "
        "\"detect_min\": %.6f, \"fresh_median\": %.6f, \"fresh_min\": %.6f}\n",
        boxes.size(), found, find.median, find.minimum, detect.median, detect.minimum, fresh.median, fresh.minimum);
    return pairs.size() == found ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4 && !(argc == 5 && (std::string(argv[4]) == "wall" || std::string(argv[4]) == "cpu"))) {
        std::fprintf(stderr, "usage: %s BOXES_FILE DIM REPEATS [wall|cpu]\n", argv[0]);
        return 2;
    }
    thread_cpu_clock = argc == 5 && std::string(argv[4]) == "cpu";
    std::ifstream file(argv[1], std::ios::binary);
    std::vector<double> raw;
    double value = 0;
    while (file.read(reinterpret_cast<char*>(&value), sizeof value)) raw.push_back(value);
    const int dim = std::atoi(argv[2]);
    const int repeats = std::max(1, std::atoi(argv[3]));
    if ((dim != 2 && dim != 3) || raw.size() % static_cast<std::size_t>(2 * dim) != 0) {
        std::fprintf(stderr, "%s: expected (N, 2, %d) float64 boxes\n", argv[1], dim);
        return 2;
    }
    return dim == 2 ? run<2>(raw, repeats) : run<3>(raw, repeats);
}
