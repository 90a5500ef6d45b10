// SPDX-License-Identifier: MIT
// Time and bytes per rank per step of smb::mpi::DistributedDetector on the paper's environment
// (docs/distributed.md). Every rank runs the same environment (the same seed) and passes the
// boxes whose id mod P is its rank, so the distribution says nothing about space; only the
// detector's calls are timed.
// Usage: mpirun -np P smb_distributed_steps N STEPS [DIM [REGIONS_CSV]] [--moving F]
// REGIONS_CSV: rank 0 writes there every rank's region after the last step (rank, then the
// mins, then the maxes; infinite at the outer faces), for scripts/plot-distributed.py.
// --moving F: at each step only a fraction F of the boxes (chosen by a hash of id and step, the
// same whatever P) take the environment's motion; the others keep last step's coordinates.
// Insertions and removals are the environment's. Default 1: every box moves, as in the paper.
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "smb/mpi/distributed_detector.hpp"
#include "smb/workload/dynamic_environment.hpp"

namespace {

template <int Dim>
void write_regions(const smb::Box<double, Dim>& mine, int rank, int ranks, const char* path) {
    std::vector<double> all(2 * Dim * static_cast<std::size_t>(ranks));
    std::vector<double> faces(mine.min.begin(), mine.min.end());
    faces.insert(faces.end(), mine.max.begin(), mine.max.end());
    MPI_Gather(faces.data(), 2 * Dim, MPI_DOUBLE, all.data(), 2 * Dim, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank != 0) return;
    std::FILE* out = std::fopen(path, "w");
    if (out == nullptr) return;
    for (int r = 0; r < ranks; ++r) {
        std::fprintf(out, "%d", r);
        for (int f = 0; f < 2 * Dim; ++f) std::fprintf(out, ",%.17g", all[static_cast<std::size_t>(r * 2 * Dim + f)]);
        std::fprintf(out, "\n");
    }
    std::fclose(out);
}

/// Whether box `id` moves at `step`: a hash (SplitMix64's finaliser) of both, below the fraction.
bool moves_at(smb::BoxId id, int step, double fraction) {
    std::uint64_t x = id * 0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(step);
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return static_cast<double>(x >> 11) * 0x1.0p-53 < fraction;
}

template <int Dim>
void run(std::size_t box_count, int steps, int rank, int ranks, const char* regions_path, double moving) {
    smb::workload::EnvironmentParams params;
    params.box_count = box_count;
    smb::workload::DynamicEnvironment<Dim> environment(params);
    smb::mpi::DistributedDetector<double, Dim> detector(MPI_COMM_WORLD);
    std::vector<smb::BoxId> ids;
    std::vector<smb::Box<double, Dim>> boxes;
    std::vector<smb::Pair> pairs;
    // Per step, summed over the steps after the first (which cuts the regions and fills the
    // Detector's order): seconds, local detection seconds, bytes of boxes, pairs and ids sent,
    // boxes in the region, boxes passed, pairs received, recuts.
    std::vector<double> sums(9, 0.0);
    std::vector<smb::BoxId> last_ids;
    std::vector<smb::Box<double, Dim>> last_boxes;
    for (int step = 0; step <= steps; ++step) {
        if (step > 0) environment.step();
        ids.swap(last_ids);
        boxes.swap(last_boxes);
        ids.clear();
        boxes.clear();
        const auto all_ids = environment.ids();
        const auto all_boxes = environment.boxes();
        std::size_t last = 0;  // both in increasing id order
        for (std::size_t i = 0; i < all_ids.size(); ++i) {
            if (all_ids[i] % static_cast<smb::BoxId>(ranks) == static_cast<smb::BoxId>(rank)) {
                while (last < last_ids.size() && last_ids[last] < all_ids[i]) ++last;
                const bool stays = last < last_ids.size() && last_ids[last] == all_ids[i] && step > 0 &&
                                   !moves_at(all_ids[i], step, moving);
                ids.push_back(all_ids[i]);
                boxes.push_back(stays ? last_boxes[last] : all_boxes[i]);
            }
        }
        MPI_Barrier(MPI_COMM_WORLD);
        detector.detect(ids, boxes, pairs);
        if (step == 0) continue;
        const auto& stats = detector.last_stats();
        const double values[9] = {stats.total_seconds,
                                  stats.local_detect_seconds,
                                  static_cast<double>(stats.box_bytes_sent),
                                  static_cast<double>(stats.pair_bytes_sent),
                                  static_cast<double>(stats.id_bytes_sent),
                                  static_cast<double>(stats.boxes_in_region),
                                  static_cast<double>(stats.boxes_passed),
                                  static_cast<double>(stats.pairs_received),
                                  stats.recut ? 1.0 : 0.0};
        for (int v = 0; v < 9; ++v) sums[static_cast<std::size_t>(v)] += values[v];
    }
    if (regions_path != nullptr) write_regions<Dim>(detector.region(), rank, ranks, regions_path);
    std::vector<double> largest(sums.size()), total(sums.size());
    MPI_Reduce(sums.data(), largest.data(), 9, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(sums.data(), total.data(), 9, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    if (rank != 0) return;
    const double s = steps, p = ranks;
    const double boxes_per_step = total[6] / s;
    std::printf("ranks %d dim %d boxes %.0f steps %d moving %g\n", ranks, Dim, boxes_per_step, steps, moving);
    std::printf("  seconds per step: slowest rank %.4f (its local detection %.4f), mean rank %.4f\n", largest[0] / s,
                largest[1] / s, total[0] / s / p);
    std::printf("  bytes sent per rank per step: boxes %.0f, pairs %.0f, ids %.0f (mean); boxes %.0f (largest)\n",
                total[2] / s / p, total[3] / s / p, total[4] / s / p, largest[2] / s);
    std::printf("  boxes in regions %.0f, ghost fraction %.4f, pairs %.0f, recuts %.0f\n", total[5] / s,
                (total[5] / s - boxes_per_step) / boxes_per_step, total[7] / s, largest[8]);
}

}  // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    double moving = 1;
    for (int a = 1; a + 1 < argc; ++a) {
        if (std::strcmp(argv[a], "--moving") != 0) continue;
        moving = std::atof(argv[a + 1]);
        for (int b = a; b + 2 < argc; ++b) argv[b] = argv[b + 2];
        argc -= 2;
        break;
    }
    const std::size_t box_count = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
    const int steps = argc > 2 ? std::atoi(argv[2]) : 10;
    const int dim = argc > 3 ? std::atoi(argv[3]) : 3;
    const char* regions_path = argc > 4 ? argv[4] : nullptr;
    if (dim == 2) {
        run<2>(box_count, steps, rank, ranks, regions_path, moving);
    } else {
        run<3>(box_count, steps, rank, ranks, regions_path, moving);
    }
    MPI_Finalize();
    return 0;
}
