// SPDX-License-Identifier: MIT
#include "run_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "counted.hpp"

namespace smb::cli {

namespace {

using StepQuantity = std::function<double(const StepRecord&)>;

double median_of(std::vector<double> values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    if (values.size() % 2 == 1) return *middle;
    const double upper = *middle;
    const double lower = *std::max_element(values.begin(), middle);
    return (lower + upper) / 2;
}

/// Spread over the steps after the build step (the first), which is reported apart.
Spread spread_after_build(const RunRecord& run, const StepQuantity& quantity) {
    if (run.steps.size() < 2) return {};
    std::vector<double> values;
    for (const auto& step : std::span(run.steps).subspan(1)) values.push_back(quantity(step));
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    const double mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
    return {median_of(values), mean, *low, *high};
}

double median_after_build(const RunRecord& run, const StepQuantity& quantity) {
    return spread_after_build(run, quantity).median;
}

double bytes_per_box(const RunRecord& run) {
    return run.final_boxes == 0 ? 0.0 : static_cast<double>(run.bytes_held) / static_cast<double>(run.final_boxes);
}

std::string duration_text(double seconds) {
    return seconds < 1 ? fmt::format("{:.3f} ms", seconds * 1e3) : fmt::format("{:.3f} s", seconds);
}

/// A median count (a double, halfway between two counts for an even number of steps) as a count.
std::uint64_t rounded(double count) { return static_cast<std::uint64_t>(std::llround(count)); }

std::string pair_text(const std::optional<Pair>& pair) {
    return pair ? fmt::format("({}, {})", pair->a, pair->b) : std::string("-");
}

const StepQuantity detect_time = [](const StepRecord& s) { return s.detect_seconds; };
const StepQuantity detect_cpu_time = [](const StepRecord& s) { return s.detect_cpu_seconds; };
const StepQuantity world_update_time = [](const StepRecord& s) { return s.world_update_seconds; };
const StepQuantity pair_count = [](const StepRecord& s) { return static_cast<double>(s.stats.pairs); };
const StepQuantity box_count = [](const StepRecord& s) { return static_cast<double>(s.stats.boxes); };
const StepQuantity update_time = [](const StepRecord& s) { return s.profile.update_seconds; };
const StepQuantity scan_time = [](const StepRecord& s) { return s.profile.scan_seconds; };
const StepQuantity containment_time = [](const StepRecord& s) { return s.profile.containment_seconds; };
const StepQuantity quantile_time = [](const StepRecord& s) { return s.profile.quantile_seconds; };
const StepQuantity list_sort_time = [](const StepRecord& s) { return s.profile.list_sort_seconds; };
const StepQuantity cut_time = [](const StepRecord& s) { return s.profile.cut_regroup_seconds; };
const StepQuantity check_time = [](const StepRecord& s) { return s.profile.check_seconds; };
const StepQuantity skin_candidates = [](const StepRecord& s) { return static_cast<double>(s.stats.skin_candidates); };
const StepQuantity skin_refreshed = [](const StepRecord& s) { return static_cast<double>(s.stats.skin_refreshed); };
const StepQuantity copy_time = [](const StepRecord& s) { return s.profile.copy_seconds; };
StepQuantity level_time(std::size_t level) {
    return [level](const StepRecord& s) { return s.profile.level_seconds[level]; };
}
const StepQuantity cell_count = [](const StepRecord& s) { return static_cast<double>(s.profile.cells); };
const StepQuantity sort_move_count = [](const StepRecord& s) { return static_cast<double>(s.profile.sort_moves); };
const StepQuantity largest_cell = [](const StepRecord& s) { return static_cast<double>(s.profile.largest_cell_boxes); };
/// One of DetectProfile's per-level counts of the paper's lists, on level `level`.
StepQuantity level_count(std::array<std::size_t, 3> DetectProfile::*counts, std::size_t level) {
    return [counts, level](const StepRecord& s) { return static_cast<double>((s.profile.*counts)[level]); };
}
/// A phase of DetectProfile: its key in --json (the field's name without "_seconds"), its label in
/// the text summary, and its time.
struct Phase {
    const char* key;
    const char* label;
    StepQuantity time;
};

/// Every phase, in the order of a detection: the keys of --json, whatever the pipeline.
std::vector<Phase> all_phases() {
    return {{"update", "update", update_time},
            {"scan", "scan", scan_time},
            {"containment", "containment", containment_time},
            {"quantile", "quantiles", quantile_time},
            {"list_sort", "list sort", list_sort_time},
            {"cut_regroup", "cut+regroup", cut_time},
            {"check", "check", check_time}};
}

/// The phases the run's pipeline has (the others stay zero): the lines of the text summary.
std::vector<Phase> phases_of(const RunRecord& run) {
    std::vector<Phase> phases;
    for (const Phase& phase : all_phases()) {
        const std::string key = phase.key;
        const bool paper = run.pipeline == "paper";
        const bool detector = run.pipeline == "detector";
        if (key == "update" && detector) continue;
        if ((key == "scan" || key == "quantile") && paper) continue;
        if (key == "containment" && run.skin == 0) continue;
        if (key == "list_sort" && !paper) continue;
        phases.push_back(phase);
    }
    return phases;
}

/// "label time, label time, ..." for the phases of the run at one step, or their medians.
template <class Value>
std::string phases_text(const RunRecord& run, Value value) {
    std::string text;
    for (const Phase& phase : phases_of(run)) {
        if (!text.empty()) text += ", ";
        text += fmt::format("{} {}", phase.label, duration_text(value(phase.time)));
    }
    return text;
}

/// The axis of level `level` in `dimension`D: the levels cut the last axis first.
char level_axis(int dimension, std::size_t level) { return "xyz"[static_cast<std::size_t>(dimension) - 1 - level]; }

}  // namespace

void print_summary_line(std::ostream& out, std::string_view label, const std::string& text) {
    out << fmt::format("  {:<22}{}\n", label, text);
}

std::string summary_duration(double seconds) { return duration_text(seconds); }

void print_summary_heading(const RunRecord& run, std::ostream& out) {
    out << fmt::format(
        "smb run: {}D, N {} -> {}, E {:g} (cube side {:.4g}), H {:g}, update factor {:g}, {}, "
        "seed {}\n",
        run.dimension, run.initial_boxes, run.final_boxes, run.packing_density, run.cube_side, run.size_ratio,
        run.update_factor, counted(run.steps.size(), "step"), run.seed);
}

void print_summary_pairs(const RunRecord& run, std::ostream& out) {
    if (run.steps.size() >= 2) {
        print_summary_line(
            out, "pairs per step",
            fmt::format("median {:.0f}, last {}", median_after_build(run, pair_count), run.steps.back().stats.pairs));
    } else if (!run.steps.empty()) {
        print_summary_line(out, "pairs", fmt::format("{}", run.steps.back().stats.pairs));
    }
}

void print_summary_check(const RunRecord& run, std::ostream& out) {
    const CheckRecord& check = run.check;
    if (!check.enabled) {
        print_summary_line(out, "check", "skipped");
    } else if (check.ok()) {
        print_summary_line(
            out, "check",
            fmt::format("OK, {} the grid reference (last: step {}, reference {})",
                        check.steps_checked == 1 ? "1 step equals" : counted(check.steps_checked, "step") + " equal",
                        check.last_checked_step, duration_text(check.last_reference_seconds)));
    } else {
        print_summary_line(
            out, "check",
            fmt::format("MISMATCH in {} of {}; step {}: {} missing (e.g. {}), {} extra "
                        "(e.g. {})",
                        check.mismatched_steps, counted(check.steps_checked, "checked step"), check.first_bad_step,
                        counted(check.missing_pairs, "pair"), pair_text(check.example_missing), check.extra_pairs,
                        pair_text(check.example_extra)));
    }
}

void print_text_summary(const RunRecord& run, std::ostream& out) {
    auto line = [&out](std::string_view label, const std::string& text) { print_summary_line(out, label, text); };
    print_summary_heading(run, out);
    const std::string rule = run.segment_rule.empty() ? std::string() : ", segment rule " + run.segment_rule;
    line("pipeline", fmt::format("{}{}, {} thread{}", run.pipeline, rule, run.threads, run.threads == 1 ? "" : "s"));
    if (!run.steps.empty()) {
        const StepRecord& build = run.steps.front();
        line("build (step 1)", fmt::format("{} ({})", duration_text(build.detect_seconds),
                                           phases_text(run, [&](const StepQuantity& time) { return time(build); })));
    }
    if (run.steps.size() >= 2) {
        const Spread detect = spread_after_build(run, detect_time);
        line(fmt::format("detect ({})", counted(run.steps.size() - 1, "step")),
             fmt::format("median {}, mean {}, min {}, max {} (CPU median {})", duration_text(detect.median),
                         duration_text(detect.mean), duration_text(detect.min), duration_text(detect.max),
                         duration_text(median_after_build(run, detect_cpu_time))));
        line("phases (median)",
             phases_text(run, [&](const StepQuantity& time) { return median_after_build(run, time); }));
        if (run.pipeline != "paper") {
            std::string levels = "copy " + duration_text(median_after_build(run, copy_time));
            for (std::size_t level = 0; level < static_cast<std::size_t>(run.dimension); ++level) {
                levels += fmt::format(", {} {}", level_axis(run.dimension, level),
                                      duration_text(median_after_build(run, level_time(level))));
            }
            line("levels (median)", levels);
        }
        if (run.skin > 0) {
            const auto rebuilt = static_cast<std::size_t>(std::count_if(
                run.steps.begin() + 1, run.steps.end(), [](const StepRecord& s) { return s.stats.skin_rebuilt; }));
            line("skin", fmt::format("{:g}: rebuilt in {} of {}; median {}, {} refreshed", run.skin, rebuilt,
                                     counted(run.steps.size() - 1, "step"),
                                     counted(rounded(median_after_build(run, skin_candidates)), "candidate"),
                                     counted(rounded(median_after_build(run, skin_refreshed)), "box", "boxes")));
        }
        line("world update (median)",
             duration_text(median_after_build(run, world_update_time)) + " in the batch calls");
    }
    print_summary_pairs(run, out);
    const std::string peak = run.peak_resident_bytes ? fmt::format(", peak RSS {:.1f} MB",
                                                                   static_cast<double>(*run.peak_resident_bytes) / 1e6)
                                                     : std::string();
    line("memory", fmt::format("{:.1f} bytes per box ({:.1f} MB held{})", bytes_per_box(run),
                               static_cast<double>(run.bytes_held) / 1e6, peak));

    print_summary_check(run, out);
}

nlohmann::ordered_json json_summary(const RunRecord& run) {
    using json = nlohmann::ordered_json;
    const bool has_later_steps = run.steps.size() >= 2;
    auto spread_json = [&](const StepQuantity& quantity) -> json {
        if (!has_later_steps) return nullptr;
        const Spread spread = spread_after_build(run, quantity);
        return {{"median", spread.median}, {"mean", spread.mean}, {"min", spread.min}, {"max", spread.max}};
    };
    auto median_json = [&](const StepQuantity& quantity) -> json {
        if (!has_later_steps) return nullptr;
        return median_after_build(run, quantity);
    };

    json summary;
    summary["dimension"] = run.dimension;
    // N drifts every step (by up to Λ·N), so the timed steps' median N is given too.
    summary["boxes"] = {{"initial", run.initial_boxes}, {"final", run.final_boxes}, {"median", median_json(box_count)}};
    summary["packing_density"] = run.packing_density;
    summary["cube_side"] = run.cube_side;
    summary["size_ratio"] = run.size_ratio;
    summary["update_factor"] = run.update_factor;
    summary["steps"] = run.steps.size();
    summary["seed"] = run.seed;
    summary["target_cell_population"] = run.target_cell_population;
    summary["pipeline"] = run.pipeline;
    summary["segment_rule"] = run.segment_rule.empty() ? json(nullptr) : json(run.segment_rule);
    summary["threads"] = run.threads;
    summary["skin"] = run.skin;
    if (run.skin > 0 && has_later_steps) {
        const auto rebuilt = std::count_if(run.steps.begin() + 1, run.steps.end(),
                                           [](const StepRecord& s) { return s.stats.skin_rebuilt; });
        summary["skin_steps"] = {{"rebuilt", rebuilt},
                                 {"candidates_median", median_after_build(run, skin_candidates)},
                                 {"refreshed_median", median_after_build(run, skin_refreshed)}};
    }
    summary["build_seconds"] = run.steps.empty() ? json(nullptr) : json(run.steps.front().detect_seconds);
    json build_phases = json::object();
    json median_phases = json::object();
    for (const Phase& phase : all_phases()) {
        if (!run.steps.empty()) build_phases[phase.key] = phase.time(run.steps.front());
        if (has_later_steps) median_phases[phase.key] = median_after_build(run, phase.time);
    }
    summary["build_phase_seconds"] = run.steps.empty() ? json(nullptr) : build_phases;
    summary["detect_seconds"] = spread_json(detect_time);
    summary["detect_cpu_seconds"] = spread_json(detect_cpu_time);
    summary["world_update_seconds_median"] = median_json(world_update_time);
    summary["phase_seconds_median"] = has_later_steps ? median_phases : json(nullptr);
    if (has_later_steps && run.pipeline != "paper") {
        json levels = json::object();
        for (std::size_t level = 0; level < static_cast<std::size_t>(run.dimension); ++level)
            levels[std::string(1, level_axis(run.dimension, level))] = median_after_build(run, level_time(level));
        summary["level_seconds_median"] = {{"copy", median_after_build(run, copy_time)}, {"levels", levels}};
    } else {
        summary["level_seconds_median"] = nullptr;
    }
    // The counts that explain the time: what the sorts moved, how the cut filled the cells, and
    // for the paper's lists each level's sorting and regrouping (docs/reproduction.md).
    if (has_later_steps) {
        json counts = {{"cells", median_after_build(run, cell_count)},
                       {"sort_moves", median_after_build(run, sort_move_count)}};
        if (run.pipeline == "paper") {
            counts["largest_cell_boxes"] = median_after_build(run, largest_cell);
            json levels = json::object();
            for (std::size_t level = 0; level < static_cast<std::size_t>(run.dimension); ++level) {
                levels[std::string(1, level_axis(run.dimension, level))] = {
                    {"sort_moves", median_after_build(run, level_count(&DetectProfile::level_sort_moves, level))},
                    {"sort_comparisons",
                     median_after_build(run, level_count(&DetectProfile::level_sort_comparisons, level))},
                    {"singular_items",
                     median_after_build(run, level_count(&DetectProfile::level_singular_items, level))},
                    {"sort_fallback_items",
                     median_after_build(run, level_count(&DetectProfile::level_sort_fallback_items, level))}};
            }
            counts["levels"] = levels;
        }
        summary["counts_median"] = counts;
    } else {
        summary["counts_median"] = nullptr;
    }
    summary["pairs"] = {{"median", median_json(pair_count)},
                        {"last", run.steps.empty() ? 0 : run.steps.back().stats.pairs}};
    summary["bytes_held"] = run.bytes_held;
    summary["bytes_per_box"] = bytes_per_box(run);
    summary["peak_rss_bytes"] = run.peak_resident_bytes ? json(*run.peak_resident_bytes) : json(nullptr);
    summary["oversized_boxes_last"] = run.steps.empty() ? 0 : run.steps.back().profile.oversized_boxes;

    const CheckRecord& check = run.check;
    json check_json = {{"enabled", check.enabled},
                       {"ok", check.ok()},
                       {"steps_checked", check.steps_checked},
                       {"mismatched_steps", check.mismatched_steps}};
    if (check.enabled && check.steps_checked > 0) {
        check_json["last_checked_step"] = check.last_checked_step;
        check_json["reference_seconds"] = check.last_reference_seconds;
    }
    if (!check.ok()) {
        check_json["first_bad_step"] = check.first_bad_step;
        check_json["missing_pairs"] = check.missing_pairs;
        check_json["extra_pairs"] = check.extra_pairs;
    }
    summary["check"] = check_json;
    return summary;
}

}  // namespace smb::cli
