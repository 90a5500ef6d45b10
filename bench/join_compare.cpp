// SPDX-License-Identifier: MIT
// Two-set (bipartite) detection, one shot: smb::find_overlapping_pairs(first, second) beside
// CGAL's box_intersection_d over the two sequences, and beside the plain way with smb (one
// detection over the union, pairs within a set dropped), on the same float boxes. Every method
// must give the same pairs (count and digest) or the run fails.
//
//   smb_join_compare --scene paper|mesh [--first N] [--second M] [--dim 2|3] [--rounds R] [--seed S]
//
// Scenes: `paper`, two independent placements of the paper's workload (E 0.4, H 2.5, the same
// cube) of N and M boxes; `mesh`, N particles of the paper's workload against the boxes of a
// triangulated height field through the middle of the cube, about M triangles (a mesh: fewer,
// larger, thin boxes). Times are the median of R rounds, each round starting with the next method: wall time,
// and in parentheses the process's CPU time (std::clock), which shows what other processes took;
// the ratio is of the CPU times, which a busy machine disturbs less.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pair_digest.hpp"
#include "smb/detector.hpp"
#include "smb/join.hpp"
#include "smb/workload/dynamic_environment.hpp"

#if defined(SMB_BENCH_HAVE_CGAL)
#include <CGAL/box_intersection_d.h>

#include "peers/cgal_box.hpp"
#endif

namespace smb::bench {
namespace {

template <int Dim>
using Boxes = std::vector<Box<float, Dim>>;

template <int Dim>
Boxes<Dim> paper_placement(std::size_t count, std::uint64_t seed, double* cube_side) {
    workload::EnvironmentParams params;
    params.box_count = count;
    params.seed = seed;
    const workload::DynamicEnvironment<Dim> environment(params);
    if (cube_side != nullptr) *cube_side = environment.cube_side();
    Boxes<Dim> boxes(environment.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (int k = 0; k < Dim; ++k) {
            boxes[i].min[k] = static_cast<float>(environment.boxes()[i].min[k]);
            boxes[i].max[k] = static_cast<float>(environment.boxes()[i].max[k]);
        }
    }
    return boxes;
}

/// The bounding boxes of a triangulated height field over the cube's floor (a segmented line in
/// 2D): height(x, y) = side/2 + side/8 sin(x/side·2π·3) cos(y/side·2π·2), about `count` boxes.
template <int Dim>
Boxes<Dim> height_field(std::size_t count, double side) {
    const double pi = std::acos(-1.0);
    auto height = [&](double x, double y) {
        return side / 2 + side / 8 * std::sin(x / side * 2 * pi * 3) * std::cos(y / side * 2 * pi * 2);
    };
    Boxes<Dim> boxes;
    if constexpr (Dim == 2) {
        const double step = side / static_cast<double>(count);
        for (std::size_t i = 0; i < count; ++i) {
            const double x0 = static_cast<double>(i) * step;
            const double h0 = height(x0, 0);
            const double h1 = height(x0 + step, 0);
            boxes.push_back({{static_cast<float>(x0), static_cast<float>(std::min(h0, h1))},
                             {static_cast<float>(x0 + step), static_cast<float>(std::max(h0, h1))}});
        }
    } else {
        const auto per_axis = static_cast<std::size_t>(std::sqrt(static_cast<double>(count) / 2));
        const double step = side / static_cast<double>(per_axis);
        for (std::size_t i = 0; i < per_axis; ++i) {
            for (std::size_t j = 0; j < per_axis; ++j) {
                const double x0 = static_cast<double>(i) * step;
                const double y0 = static_cast<double>(j) * step;
                const double h00 = height(x0, y0);
                const double h10 = height(x0 + step, y0);
                const double h01 = height(x0, y0 + step);
                const double h11 = height(x0 + step, y0 + step);
                // Two triangles per square: (00, 10, 11) and (00, 11, 01).
                for (const auto& [ha, hb] : {std::pair{h10, h11}, std::pair{h11, h01}}) {
                    const double lo = std::min({h00, ha, hb});
                    const double hi = std::max({h00, ha, hb});
                    boxes.push_back(
                        {{static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(lo)},
                         {static_cast<float>(x0 + step), static_cast<float>(y0 + step), static_cast<float>(hi)}});
                }
            }
        }
    }
    return boxes;
}

struct Outcome {
    double seconds = 0;
    std::size_t pairs = 0;
    std::uint64_t digest = 0;
};

/// The pairs as one-set pairs (a, count_first + b), so that digest_pairs can check them.
std::uint64_t digest_cross(std::vector<Pair>& pairs, std::size_t count_first) {
    for (Pair& pair : pairs) pair.b += count_first;
    return digest_pairs(pairs);
}

template <int Dim>
Outcome run_smb(const Boxes<Dim>& first, const Boxes<Dim>& second) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Pair> pairs = find_overlapping_pairs(first, second);
    const auto stop = std::chrono::steady_clock::now();
    const std::size_t count = pairs.size();
    return {std::chrono::duration<double>(stop - start).count(), count, digest_cross(pairs, first.size())};
}

/// The plain way: one Detector over the concatenation, the pairs within a set dropped.
template <int Dim>
Outcome run_smb_union(const Boxes<Dim>& first, const Boxes<Dim>& second) {
    const auto start = std::chrono::steady_clock::now();
    Boxes<Dim> both;
    both.reserve(first.size() + second.size());
    both.insert(both.end(), first.begin(), first.end());
    both.insert(both.end(), second.begin(), second.end());
    std::vector<Pair> pairs;
    Detector<float, Dim> detector;
    const std::size_t split = first.size();
    detector.detect(both, [&](std::span<const Pair> chunk) {
        for (const Pair& pair : chunk) {
            if (pair.a < split && pair.b >= split) pairs.push_back({pair.a, pair.b - split});
        }
    });
    std::sort(pairs.begin(), pairs.end());
    const auto stop = std::chrono::steady_clock::now();
    const std::size_t count = pairs.size();
    return {std::chrono::duration<double>(stop - start).count(), count, digest_cross(pairs, first.size())};
}

#if defined(SMB_BENCH_HAVE_CGAL)
/// CGAL's time covers the copy into its box type and the calls; its pairs come unsorted, and
/// sorting them is timed apart (`sort_seconds`), since smb's result is sorted.
template <int Dim>
Outcome run_cgal(const Boxes<Dim>& first, const Boxes<Dim>& second, double& sort_seconds) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<CgalBox<Dim>> a(first.size());
    std::vector<CgalBox<Dim>> b(second.size());
    for (std::size_t i = 0; i < first.size(); ++i) a[i] = {first[i].min, first[i].max, i};
    for (std::size_t j = 0; j < second.size(); ++j) b[j] = {second[j].min, second[j].max, first.size() + j};
    std::vector<Pair> pairs;
    const std::size_t split = first.size();
    auto report = [&pairs, split](const CgalBox<Dim>& x, const CgalBox<Dim>& y) {
        pairs.push_back(x.index < split ? Pair{x.index, y.index - split} : Pair{y.index, x.index - split});
    };
    CGAL::box_intersection_d(a.begin(), a.end(), b.begin(), b.end(), report, std::ptrdiff_t{10},
                             CGAL::Box_intersection_d::CLOSED, CGAL::Box_intersection_d::BIPARTITE);
    const auto stop = std::chrono::steady_clock::now();
    std::sort(pairs.begin(), pairs.end());
    sort_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - stop).count();
    const std::size_t count = pairs.size();
    return {std::chrono::duration<double>(stop - start).count(), count, digest_cross(pairs, first.size())};
}
#endif

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

template <int Dim>
int compare(const std::string& scene, std::size_t count_first, std::size_t count_second, int rounds,
            std::uint64_t seed) {
    double side = 0;
    const Boxes<Dim> first = paper_placement<Dim>(count_first, seed, &side);
    const Boxes<Dim> second = scene == "paper" ? paper_placement<Dim>(count_second, seed + 1, nullptr)
                                               : height_field<Dim>(count_second, side);

    std::map<std::string, std::vector<double>> times;
    std::map<std::string, Outcome> last;
    std::vector<double> cgal_sort;
    std::map<std::string, std::vector<double>> cpu;
    // The processor time beside the wall time shows how much other processes took.
    auto timed = [&](const std::string& name, const std::function<Outcome()>& method) {
        const std::clock_t start = std::clock();
        const Outcome outcome = method();
        cpu[name].push_back(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
        times[name].push_back(outcome.seconds);
        last[name] = outcome;
    };
    std::vector<std::pair<std::string, std::function<Outcome()>>> methods{
        {"smb", [&] { return run_smb(first, second); }},
        {"smb union", [&] { return run_smb_union(first, second); }},
    };
#if defined(SMB_BENCH_HAVE_CGAL)
    methods.emplace_back("cgal", [&] {
        double sort_seconds = 0;
        const Outcome cgal = run_cgal(first, second, sort_seconds);
        cgal_sort.push_back(sort_seconds);
        return cgal;
    });
#endif
    // Each round starts with the next method, so that none always runs first (after the scene
    // was built) or always after the same other one.
    for (int round = 0; round < rounds; ++round) {
        for (std::size_t m = 0; m < methods.size(); ++m) {
            const auto& [name, method] = methods[(m + static_cast<std::size_t>(round)) % methods.size()];
            timed(name, method);
        }
    }
    bool agree = true;
    for (const auto& [name, outcome] : last)
        agree = agree && outcome.pairs == last["smb"].pairs && outcome.digest == last["smb"].digest;

    std::printf("| %dD %s | %zu | %zu | %zu | %016llx | %.3f (%.3f) | %.3f (%.3f) |", Dim, scene.c_str(), first.size(),
                second.size(), last["smb"].pairs, static_cast<unsigned long long>(last["smb"].digest),
                median(times["smb"]), median(cpu["smb"]), median(times["smb union"]), median(cpu["smb union"]));
    if (times.contains("cgal")) {
        std::printf(" %.3f (%.3f) +%.3f sort | %.2fx |", median(times["cgal"]), median(cpu["cgal"]), median(cgal_sort),
                    median(cpu["cgal"]) / median(cpu["smb"]));
    } else {
        std::printf(" - | - |");
    }
    std::printf(" %s |\n", agree ? "yes" : "NO");
    return agree ? 0 : 1;
}

int main_with_arguments(int argc, char** argv) {
    std::map<std::string, std::string> values{{"scene", "paper"}, {"first", "100000"}, {"second", "100000"},
                                              {"dim", "3"},       {"rounds", "3"},     {"seed", "1"}};
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--header") {
            std::printf(
                "| scene | first | second | pairs | digest | smb, s (CPU) | smb union, s (CPU) | "
                "CGAL, s (CPU) | CGAL ÷ smb, CPU | same pairs |\n|---|---|---|---|---|---|---|---|---|---|\n");
            continue;
        }
        if (!flag.starts_with("--") || i + 1 >= argc || !values.contains(flag.substr(2)))
            throw std::invalid_argument("unknown or incomplete option " + flag);
        values[flag.substr(2)] = argv[++i];
    }
    const std::string scene = values["scene"];
    if (scene != "paper" && scene != "mesh") throw std::invalid_argument("--scene is paper or mesh");
    const auto first = std::stoull(values["first"]);
    const auto second = std::stoull(values["second"]);
    const int rounds = std::stoi(values["rounds"]);
    const auto seed = std::stoull(values["seed"]);
    if (values["dim"] == "2") return compare<2>(scene, first, second, rounds, seed);
    return compare<3>(scene, first, second, rounds, seed);
}

}  // namespace
}  // namespace smb::bench

int main(int argc, char** argv) {
    try {
        return smb::bench::main_with_arguments(argc, argv);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "smb_join_compare: %s\n", error.what());
        return 64;
    }
}
