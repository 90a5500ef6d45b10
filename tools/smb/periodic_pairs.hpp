// SPDX-License-Identifier: MIT
#pragma once
// `smb pairs --periodic`: the option's axes, and the periodic pair CSV of every frame (header
// frame,a,b,sx,sy[,sz]; s the image shift of b relative to a; rows sorted by (frame, a, b)).

#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "scene_csv.hpp"

namespace smb::cli {

/// The axes of --periodic, in x, y[, z] order: [lo, hi) where periodic, nothing where '-'.
using PeriodicAxes = std::vector<std::optional<std::pair<double, double>>>;

/// Parses "X0:X1,Y0:Y1[,Z0:Z1]" (an axis '-' is not periodic); throws std::invalid_argument
/// with the problem (two or three axes, finite numbers, lo < hi).
[[nodiscard]] PeriodicAxes parse_periodic_axes(const std::string& text);

/// Follows the scene through one World, frame by frame, and writes the periodic pair CSV.
/// Throws CLI::ValidationError if `axes` does not name one interval per axis of the scene.
void write_periodic_pairs(io::SceneReader& reader, std::ostream& out, const PeriodicAxes& axes);

}  // namespace smb::cli
