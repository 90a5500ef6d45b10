// SPDX-License-Identifier: MIT
#include "distributed_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <exception>
#include <iostream>
#include <iterator>
#include <vector>

#include "exit_status.hpp"
#include "mpi_run.hpp"
#include "pair_counts_file.hpp"
#include "peak_memory.hpp"
#include "ring_reference.hpp"
#include "run_report.hpp"
#include "smb/mpi/distributed_detector.hpp"
#include "smb/workload/environment_share.hpp"

namespace smb::cli {

namespace {

/// What rank 0 reports beyond the serial summary, per step after the first.
struct DistributedRecord {
    int ranks = 1;
    std::vector<double> generate_seconds;  ///< the slowest rank's step of its share
    std::vector<double> box_bytes;         ///< mean over the ranks of the bytes of boxes sent
    std::vector<double> pair_bytes;        ///< ... of pairs
    std::vector<double> id_bytes;          ///< ... of ids (the duplicate check)
    std::vector<double> ghost_fractions;   ///< boxes in all regions over boxes, less 1
    std::size_t recuts = 0;
    std::size_t largest_peak_rss = 0;
};

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    if (values.size() % 2 == 1) return *middle;
    return (*middle + *std::max_element(values.begin(), middle)) / 2;
}

/// The pairs of this rank against the ring reference, summed over the ranks into `check` on
/// every rank, as the serial command's check_step records them. Collective.
template <int Dim>
void check_step(const workload::EnvironmentShare<Dim>& share, const std::vector<Pair>& detected, std::size_t step,
                CheckRecord& check) {
    const auto start = Clock::now();
    const std::vector<Pair> expected = ring_reference_pairs<Dim>(MPI_COMM_WORLD, share.ids(), share.boxes());
    double seconds = seconds_since(start);
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    check.last_reference_seconds = seconds;
    ++check.steps_checked;
    check.last_checked_step = step;

    std::vector<Pair> missing, extra;
    std::set_difference(expected.begin(), expected.end(), detected.begin(), detected.end(),
                        std::back_inserter(missing));
    std::set_difference(detected.begin(), detected.end(), expected.begin(), expected.end(), std::back_inserter(extra));
    std::array<unsigned long long, 2> counts = {missing.size(), extra.size()};
    MPI_Allreduce(MPI_IN_PLACE, counts.data(), 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (counts[0] == 0 && counts[1] == 0) return;
    // The examples are the smallest pair missing and extra over all ranks, as the serial
    // command's sorted lists give them.
    const auto first_or_none = [](const std::vector<Pair>& list) {
        return list.empty() ? std::array<BoxId, 2>{~BoxId{0}, ~BoxId{0}} : std::array<BoxId, 2>{list[0].a, list[0].b};
    };
    std::array<BoxId, 4> mine{};
    const auto first_missing = first_or_none(missing), first_extra = first_or_none(extra);
    std::copy(first_missing.begin(), first_missing.end(), mine.begin());
    std::copy(first_extra.begin(), first_extra.end(), mine.begin() + 2);
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    std::vector<BoxId> all(4 * static_cast<std::size_t>(ranks));
    MPI_Allgather(mine.data(), 4, MPI_UINT64_T, all.data(), 4, MPI_UINT64_T, MPI_COMM_WORLD);
    std::array<BoxId, 4> smallest{~BoxId{0}, ~BoxId{0}, ~BoxId{0}, ~BoxId{0}};
    for (std::size_t r = 0; r < all.size(); r += 4) {
        if (Pair{all[r], all[r + 1]} < Pair{smallest[0], smallest[1]}) smallest[0] = all[r], smallest[1] = all[r + 1];
        if (Pair{all[r + 2], all[r + 3]} < Pair{smallest[2], smallest[3]})
            smallest[2] = all[r + 2], smallest[3] = all[r + 3];
    }
    if (check.mismatched_steps++ == 0) {
        check.first_bad_step = step;
        check.missing_pairs = counts[0];
        check.extra_pairs = counts[1];
        if (counts[0] > 0) check.example_missing = Pair{smallest[0], smallest[1]};
        if (counts[1] > 0) check.example_extra = Pair{smallest[2], smallest[3]};
    }
}

void print_distributed_summary(const RunRecord& run, const DistributedRecord& distributed, std::ostream& out) {
    print_summary_heading(run, out);
    print_summary_line(
        out, "pipeline",
        fmt::format("distributed over {} rank{} (smb::mpi, a Detector in each region), {} thread{} each",
                    distributed.ranks, distributed.ranks == 1 ? "" : "s", run.threads, run.threads == 1 ? "" : "s"));
    if (!run.steps.empty()) {
        print_summary_line(out, "build (step 1)",
                           summary_duration(run.steps.front().detect_seconds) + " (slowest rank)");
    }
    if (run.steps.size() >= 2) {
        std::vector<double> detect;
        for (std::size_t s = 1; s < run.steps.size(); ++s) detect.push_back(run.steps[s].detect_seconds);
        print_summary_line(
            out, fmt::format("detect ({} steps)", detect.size()),
            fmt::format("median {}, max {} (slowest rank of each step)", summary_duration(median(detect)),
                        summary_duration(*std::max_element(detect.begin(), detect.end()))));
        print_summary_line(out, "generate (median)",
                           summary_duration(median(distributed.generate_seconds)) + " (slowest rank's share)");
        print_summary_line(
            out, "sent (median)",
            fmt::format("boxes {:.0f} B, pairs {:.0f} B, ids {:.0f} B per rank (mean over the ranks)",
                        median(distributed.box_bytes), median(distributed.pair_bytes), median(distributed.id_bytes)));
        print_summary_line(out, "ghosts (median)",
                           fmt::format("{:.4f} of the boxes; {} recut{}", median(distributed.ghost_fractions),
                                       distributed.recuts, distributed.recuts == 1 ? "" : "s"));
    }
    print_summary_pairs(run, out);
    print_summary_line(
        out, "memory",
        fmt::format("peak RSS {:.1f} MB (largest rank)", static_cast<double>(distributed.largest_peak_rss) / 1e6));
    print_summary_check(run, out);
}

nlohmann::ordered_json distributed_json(const RunRecord& run, const DistributedRecord& distributed) {
    nlohmann::ordered_json summary = json_summary(run);
    // The serial command's phases, levels and memory of one World do not exist here.
    for (const char* key :
         {"build_phase_seconds", "phase_seconds_median", "level_seconds_median", "world_update_seconds_median",
          "bytes_held", "bytes_per_box", "oversized_boxes_last", "detect_cpu_seconds", "skin"}) {
        summary.erase(key);
    }
    summary["ranks"] = distributed.ranks;
    summary["generate_seconds_median"] = median(distributed.generate_seconds);
    summary["bytes_sent_per_rank_median"] = {{"boxes", median(distributed.box_bytes)},
                                             {"pairs", median(distributed.pair_bytes)},
                                             {"ids", median(distributed.id_bytes)}};
    summary["ghost_fraction_median"] = median(distributed.ghost_fractions);
    summary["recuts"] = distributed.recuts;
    summary["peak_rss_bytes"] = distributed.largest_peak_rss;
    return summary;
}

template <int Dim>
int run_in(const workload::EnvironmentParams& params, std::size_t steps, const DistributedRunOptions& options, int rank,
           int ranks) {
    workload::EnvironmentShare<Dim> share(params, rank, ranks);
    mpi::DistributedSettings settings;
    settings.detector.target_cell_population = options.target_cell_population;
    settings.detector.threads = options.threads;
    mpi::DistributedDetector<double, Dim> detector(MPI_COMM_WORLD, settings);

    RunRecord run;
    run.dimension = Dim;
    run.initial_boxes = share.global_size();
    run.packing_density = share.packing_density();
    run.cube_side = share.cube_side();
    run.size_ratio = params.size_ratio;
    run.update_factor = params.update_factor;
    run.seed = params.seed;
    run.target_cell_population = options.target_cell_population;
    run.pipeline = "distributed";
    run.threads = options.threads;
    run.check.enabled = options.check;
    DistributedRecord distributed;
    distributed.ranks = ranks;

    std::vector<Pair> pairs;
    for (std::size_t step = 1; step <= steps; ++step) {
        auto start = Clock::now();
        if (step > 1) share.step();
        const double generate_seconds = seconds_since(start);
        start = Clock::now();
        detector.detect(share.ids(), share.boxes(), pairs);  // bad input throws on every rank alike
        const auto& stats = detector.last_stats();
        std::array<double, 2> slowest = {seconds_since(start), generate_seconds};
        std::array<double, 5> sums = {static_cast<double>(pairs.size()), static_cast<double>(stats.boxes_in_region),
                                      static_cast<double>(stats.box_bytes_sent),
                                      static_cast<double>(stats.pair_bytes_sent),
                                      static_cast<double>(stats.id_bytes_sent)};
        MPI_Allreduce(MPI_IN_PLACE, slowest.data(), 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        MPI_Allreduce(MPI_IN_PLACE, sums.data(), 5, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
        StepRecord record;
        record.detect_seconds = slowest[0];
        record.stats.pairs = static_cast<std::size_t>(sums[0]);
        record.stats.boxes = share.global_size();
        run.steps.push_back(record);
        if (step > 1) {
            const double boxes = static_cast<double>(std::max<std::size_t>(share.global_size(), 1));
            distributed.generate_seconds.push_back(slowest[1]);
            distributed.box_bytes.push_back(sums[2] / ranks);
            distributed.pair_bytes.push_back(sums[3] / ranks);
            distributed.id_bytes.push_back(sums[4] / ranks);
            distributed.ghost_fractions.push_back(sums[1] / boxes - 1);
            distributed.recuts += stats.recut ? 1 : 0;
        }

        const bool scheduled = options.check_every > 0 && step % options.check_every == 0;
        if (run.check.enabled && (scheduled || step == steps)) {
            sort_pairs(pairs);
            check_step(share, pairs, step, run.check);
        }
    }
    run.final_boxes = share.global_size();
    const unsigned long long peak = peak_resident_bytes().value_or(0);
    unsigned long long largest_peak = 0;
    MPI_Reduce(&peak, &largest_peak, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, 0, MPI_COMM_WORLD);
    distributed.largest_peak_rss = largest_peak;

    if (rank == 0) {
        if (!options.pair_counts.empty()) write_pair_counts(run, options.pair_counts);
        if (options.json) {
            std::cout << distributed_json(run, distributed).dump(2) << '\n';
        } else {
            print_distributed_summary(run, distributed, std::cout);
        }
    }
    return run.check.ok() ? exit_status::success : exit_status::mismatch;
}

}  // namespace

int run_distributed_environment(const EnvironmentOptions& environment, const DistributedRunOptions& options) {
    MpiRun mpi_run;
    const int rank = mpi_run.rank();
    int status = exit_status::failure;
    try {
        // The same parameters on every rank: a refusal is the same everywhere, before any message.
        const workload::EnvironmentParams params = environment.params();
        status = environment.dimension == 2 ? run_in<2>(params, environment.steps, options, rank, mpi_run.ranks())
                                            : run_in<3>(params, environment.steps, options, rank, mpi_run.ranks());
    } catch (const std::exception&) {
        if (rank != 0) return exit_status::failure;  // rank 0 says what went wrong
        throw;
    }
    return status;
}

}  // namespace smb::cli
