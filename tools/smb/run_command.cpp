// SPDX-License-Identifier: MIT
#include "run_command.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <iostream>
#include <iterator>
#include <thread>
#include <vector>

#include "exit_status.hpp"
#include "option_checks.hpp"
#include "pair_counts_file.hpp"
#include "peak_memory.hpp"
#include "progress_bar.hpp"
#include "run_report.hpp"
#include "smb/detector.hpp"
#include "smb/workload/reference_grid.hpp"
#include "smb/workload/swap_remove_mirror.hpp"
#include "smb/workload/world_sync.hpp"
#include "smb/world.hpp"
#ifdef SMB_CLI_HAS_MPI
#include "distributed_run.hpp"
#endif

namespace smb::cli {

namespace {

/// Compares one detection (sorted) with the reference and records the outcome.
template <int Dim>
void check_step(const workload::DynamicEnvironment<Dim>& environment, const std::vector<Pair>& detected,
                std::size_t step, CheckRecord& check) {
    const auto start = Clock::now();
    const std::vector<Pair> expected = workload::grid_pairs<double, Dim>(environment.ids(), environment.boxes());
    check.last_reference_seconds = seconds_since(start);
    ++check.steps_checked;
    check.last_checked_step = step;
    if (detected == expected) return;

    std::vector<Pair> missing;
    std::vector<Pair> extra;
    std::set_difference(expected.begin(), expected.end(), detected.begin(), detected.end(),
                        std::back_inserter(missing));
    std::set_difference(detected.begin(), detected.end(), expected.begin(), expected.end(), std::back_inserter(extra));
    // On sorted ranges set_difference counts multiplicity, so a repeated pair shows up as extra.
    if (check.mismatched_steps++ == 0) {
        check.first_bad_step = step;
        check.missing_pairs = missing.size();
        check.extra_pairs = extra.size();
        if (!missing.empty()) check.example_missing = missing.front();
        if (!extra.empty()) check.example_extra = extra.front();
    }
}

}  // namespace

RunCommand::RunCommand(CLI::App& parent)
    : app_(parent.add_subcommand("run",
                                 "Run the paper's artificial dynamic environment in memory, time "
                                 "every detection and check the last one")) {
    add_environment_options(*app_, environment_);
    target_cell_population_ = WorldSettings{}.target_cell_population;
    app_->add_option("--cell-population", target_cell_population_,
                     "boxes the axial cuts aim to put in one cell (DetectionSettings)")
        ->check(at_least(1))
        ->capture_default_str();
    // DetectionSettings::threads takes at most 1024 (include/smb/settings.hpp); said here as an
    // argument error rather than as the library's.
    app_->add_option("--threads", threads_,
                     "threads detect() may use; 0 for as many as OpenMP offers (DetectionSettings)")
        ->check(in_closed_range(0, 1024))
        ->capture_default_str();
    auto* pipeline = app_->add_option("--pipeline", pipeline_,
                                      "persistent: the default pipeline (persistent cuts); paper: the paper's "
                                      "lists as written (WorldSettings::pipeline); detector: persistent cuts "
                                      "through smb::Detector, over the environment's own array of boxes")
                         ->check(CLI::IsMember({"persistent", "paper", "detector"}))
                         ->capture_default_str();
    auto* segment_rule =
        app_->add_option("--segment-rule", segment_rule_,
                         "paper pipeline only: count: the segments per axis from N and --cell-population; paper: "
                         "as many at most, each at least twice the largest box on its axis, as the paper keeps "
                         "them (WorldSettings::segment_rule)")
            ->check(CLI::IsMember({"count", "paper"}))
            ->capture_default_str();
    auto* skin = app_->add_option("--skin", skin_,
                                  "grow every box by this much on each side and keep the pairs of grown boxes "
                                  "from step to step (WorldSettings::skin, DetectorSettings::skin; 0: off; not "
                                  "with --pipeline paper)")
                     ->check(at_least(0))
                     ->capture_default_str();
    auto* check_every = app_->add_option("--check-every", check_every_,
                                         "also check every K-th step against the grid reference "
                                         "(the last step is always checked)")
                            ->check(not_negative());
    app_->add_flag("--no-check", no_check_, "skip the reference check")->excludes(check_every);
    app_->add_flag("--json", json_, "print the summary as one JSON object on standard output");
    app_->add_flag("--no-progress", no_progress_, "never draw the progress bar");
    app_->add_option("--pair-counts", pair_counts_, "write the number of pairs of every step to this CSV (step,pairs)");
#ifdef SMB_CLI_HAS_MPI
    app_->add_flag("--distributed", distributed_,
                   "run over the ranks of an MPI run (mpirun -np P smb run --distributed ...): each rank generates "
                   "the boxes whose id mod P is its rank, smb::mpi detects; the same scene, pairs and check")
        ->excludes(pipeline)
        ->excludes(segment_rule)
        ->excludes(skin);
#else
    (void)pipeline;
    (void)segment_rule;
    (void)skin;
#endif
}

int RunCommand::run() const {
    if (skin_ > 0 && pipeline_ == "paper")
        throw CLI::ValidationError("--skin",
                                   "needs --pipeline persistent or detector (the paper's lists keep no skin)");
    if (segment_rule_ != "count" && pipeline_ != "paper")
        throw CLI::ValidationError("--segment-rule", "needs --pipeline paper");
#ifdef SMB_CLI_HAS_MPI
    if (distributed_) {
        return run_distributed_environment(
            environment_, {target_cell_population_, threads_, check_every_, !no_check_, json_, pair_counts_});
    }
#endif
    return environment_.dimension == 2 ? run_in<2>() : run_in<3>();
}

template <int Dim>
int RunCommand::run_in() const {
    workload::DynamicEnvironment<Dim> environment(environment_.params());
    WorldSettings settings;
    settings.target_cell_population = target_cell_population_;
    settings.threads = threads_;
    settings.pipeline = pipeline_ == "paper" ? Pipeline::paper_lists : Pipeline::persistent_cuts;
    settings.segment_rule = segment_rule_ == "paper" ? SegmentRule::twice_largest_box : SegmentRule::from_count;
    settings.skin = skin_;
    settings.profile = true;  // the summary prints the phases
    World<double, Dim> world(settings);
    // The detector reads an array in which each body keeps its index (as an array-based
    // simulation's would: smb/workload/swap_remove_mirror.hpp); keeping it up is the update's time. Its pairs
    // are indices into that array, turned into ids (outside the timing) where a step is checked.
    const bool through_detector = pipeline_ == "detector";
    workload::SwapRemoveMirror<Box<double, Dim>> mirror;
    const DetectorSettings detector_settings{settings, skin_};  // the shared settings, and the skin
    Detector<double, Dim> detector(detector_settings);

    RunRecord run;
    run.dimension = Dim;
    run.initial_boxes = environment.size();
    run.packing_density = environment.packing_density();
    run.cube_side = environment.cube_side();
    run.size_ratio = environment_.size_ratio;
    run.update_factor = environment_.update_factor;
    run.seed = environment_.seed;
    run.target_cell_population = target_cell_population_;
    run.pipeline = pipeline_;
    if (pipeline_ == "paper") run.segment_rule = segment_rule_;
    run.skin = skin_;
    run.threads = settings.pipeline == Pipeline::paper_lists || !openmp_enabled() ? 1
                  : threads_ == 0                                                 ? std::thread::hardware_concurrency()
                                                                                  : threads_;
    run.check.enabled = !no_check_;

    const std::size_t steps = environment_.steps;
    ProgressBar progress(steps, !no_progress_ && standard_error_is_terminal());
    std::vector<Pair> pairs;
    for (std::size_t step = 1; step <= steps; ++step) {
        if (step > 1) environment.step();
        StepRecord record;
        auto start = Clock::now();
        if (through_detector) {
            const auto& changes = environment.changes();
            mirror.follow(changes.removed_ids, changes.inserted_ids, environment.ids(), environment.boxes());
        } else {
            workload::apply_changes(environment.changes(), world);
        }
        record.world_update_seconds = seconds_since(start);
        pairs.clear();  // last step's pairs are not needed: detect() has none to keep
        start = Clock::now();
        const std::clock_t cpu_start = std::clock();
        record.stats = through_detector ? detector.detect(mirror.boxes(), pairs) : world.detect(pairs);
        record.detect_cpu_seconds = static_cast<double>(std::clock() - cpu_start) / static_cast<double>(CLOCKS_PER_SEC);
        record.detect_seconds = seconds_since(start);
        record.profile = through_detector ? detector.last_profile() : world.last_profile();
        run.steps.push_back(record);

        const bool scheduled = check_every_ > 0 && step % check_every_ == 0;
        if (run.check.enabled && (scheduled || step == steps)) {
            if (through_detector) {
                for (Pair& pair : pairs) {
                    const BoxId a = mirror.id_at(pair.a);
                    const BoxId b = mirror.id_at(pair.b);
                    pair = a < b ? Pair{a, b} : Pair{b, a};
                }
            }
            sort_pairs(pairs);
            check_step(environment, pairs, step, run.check);
        }
        progress.update(step, record.detect_seconds);
    }
    progress.finish();
    run.final_boxes = environment.size();
    run.bytes_held = through_detector ? detector.bytes_held() : world.bytes_held();
    run.peak_resident_bytes = peak_resident_bytes();
    if (!pair_counts_.empty()) write_pair_counts(run, pair_counts_);

    if (json_) {
        std::cout << json_summary(run).dump(2) << '\n';
    } else {
        print_text_summary(run, std::cout);
    }
    return run.check.ok() ? exit_status::success : exit_status::mismatch;
}

}  // namespace smb::cli
