// SPDX-License-Identifier: MIT
#pragma once
// What `smb run` measured, and its two renderings: a short text summary and one JSON object.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "smb/pair.hpp"
#include "smb/profile.hpp"
#include "smb/stats.hpp"

namespace smb::cli {

using Clock = std::chrono::steady_clock;

/// Wall seconds since `start`, as `smb run` and its distributed form time their steps.
[[nodiscard]] inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct StepRecord {
    double world_update_seconds = 0;  ///< the batch insert / remove / update calls
    double detect_seconds = 0;        ///< wall time of detect()
    /// Processor time of detect() (std::clock: this process's CPU time on POSIX systems). Next to
    /// the wall time it shows whether other processes took the CPU away during the step.
    double detect_cpu_seconds = 0;
    DetectStats stats;
    DetectProfile profile;
};

/// Outcome of comparing detections with the grid reference.
struct CheckRecord {
    bool enabled = false;
    std::size_t steps_checked = 0;
    std::size_t mismatched_steps = 0;
    std::size_t last_checked_step = 0;  ///< 1-based
    double last_reference_seconds = 0;
    // Details of the first mismatch.
    std::size_t first_bad_step = 0;
    std::size_t missing_pairs = 0;  ///< found by the reference, not by detect()
    std::size_t extra_pairs = 0;    ///< reported by detect(), not by the reference
    std::optional<Pair> example_missing;
    std::optional<Pair> example_extra;

    [[nodiscard]] bool ok() const noexcept { return mismatched_steps == 0; }
};

struct RunRecord {
    int dimension = 3;
    std::size_t initial_boxes = 0;
    std::size_t final_boxes = 0;
    double packing_density = 0;
    double cube_side = 0;
    double size_ratio = 0;
    double update_factor = 0;
    std::uint64_t seed = 0;
    std::size_t target_cell_population = 0;
    std::string pipeline;      ///< "persistent", "paper" or "detector"
    std::string segment_rule;  ///< the paper pipeline's: "count" or "paper"; empty for the others
    std::size_t threads = 1;   ///< threads detect() used
    double skin = 0;           ///< DetectorSettings::skin of the detector (0: none)
    std::vector<StepRecord> steps;
    std::size_t bytes_held = 0;  ///< world.bytes_held() after the last step
    /// The process's peak resident memory at the end: the world, the environment that feeds it
    /// and the pair list (plus the reference check's grid when the check ran).
    std::optional<std::size_t> peak_resident_bytes;
    CheckRecord check;
};

/// Median, mean, minimum and maximum of one quantity over the steps after the first. The mean
/// carries the rare costly steps (a skin's rebuild, a group cut again) that the median hides.
struct Spread {
    double median = 0;
    double mean = 0;
    double min = 0;
    double max = 0;
};

void print_text_summary(const RunRecord& run, std::ostream& out);
[[nodiscard]] nlohmann::ordered_json json_summary(const RunRecord& run);

// Parts of the text summary, for `smb run --distributed`, whose heading, pairs and check lines
// must read as the serial command's.
/// "  label                 text": one line of the summary.
void print_summary_line(std::ostream& out, std::string_view label, const std::string& text);
/// A duration as the summary writes it (ms below a second).
[[nodiscard]] std::string summary_duration(double seconds);
/// The first line: the scene's parameters and the number of steps.
void print_summary_heading(const RunRecord& run, std::ostream& out);
/// "pairs per step" (median and last), or "pairs" for a run of one step.
void print_summary_pairs(const RunRecord& run, std::ostream& out);
/// The check's outcome against the grid reference.
void print_summary_check(const RunRecord& run, std::ostream& out);

}  // namespace smb::cli
