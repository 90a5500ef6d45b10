// SPDX-License-Identifier: MIT
#pragma once
// `smb run --pair-counts FILE`: the number of pairs found at every step, one CSV row per step.

#include <string>

#include "run_report.hpp"

namespace smb::cli {

/// Writes "step,pairs" and then one row per step of `run` (steps count from 1) to `path` ("-":
/// standard output). Throws std::runtime_error when the file cannot be written.
void write_pair_counts(const RunRecord& run, const std::string& path);

}  // namespace smb::cli
