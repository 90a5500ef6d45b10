// SPDX-License-Identifier: MIT
#include "environment_options.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "option_checks.hpp"

namespace smb::cli {

workload::EnvironmentParams EnvironmentOptions::params() const {
    check_cube_side();
    workload::EnvironmentParams params;
    params.box_count = box_count;
    params.packing_density = packing_density;
    if (side_option != nullptr && side_option->count() > 0) params.cube_side = cube_side;
    params.size_ratio = size_ratio;
    params.update_factor = update_factor;
    params.seed = seed;
    return params;
}

void EnvironmentOptions::check_cube_side() const {
    // The environment refuses a cube narrower than its largest box side b = 1; said here so that
    // the side reads as the user gave it, or derived from E in shortest form.
    constexpr double largest_side = 1;
    const bool side_given = side_option != nullptr && side_option->count() > 0;
    const double side = side_given
                            ? cube_side
                            : workload::cube_side_for_density(box_count, packing_density, largest_side / size_ratio,
                                                              largest_side, dimension);
    if (side >= largest_side) return;
    if (!side_given && box_count == 0)
        throw std::invalid_argument("an empty scene (N = 0) has no cube side at a density: give --side");
    const std::string side_text = side_given ? side_option->results().front() : fmt::format("{}", side);
    throw std::invalid_argument(fmt::format("the cube side x = {} is smaller than the largest box side b = 1 ({})",
                                            side_text, side_given ? "raise --side" : "lower E or raise N"));
}

void add_environment_options(CLI::App& command, EnvironmentOptions& options) {
    command.add_option("--dim", options.dimension, "dimension of the boxes")
        ->check(CLI::IsMember({2, 3}))
        ->capture_default_str();
    command.add_option("-n,--boxes", options.box_count, "number of boxes N at the first step")
        ->check(not_negative())
        ->capture_default_str();
    auto* density = command
                        .add_option("-E,--density", options.packing_density,
                                    "packing density E = N((a+b)/2)^dim / x^dim; sets the cube side x")
                        ->check(greater_than(0))
                        ->capture_default_str();
    options.side_option =
        command.add_option("--side", options.cube_side, "cube side x instead of --density (E is then derived)")
            ->check(greater_than(0))
            ->excludes(density);
    command
        .add_option("-H,--size-ratio", options.size_ratio,
                    "size ratio H = b/a of the largest to the smallest side (b = 1)")
        ->check(in_closed_range(1, 1e12))
        ->capture_default_str();
    command
        .add_option("-L,--update-factor", options.update_factor,
                    "update factor: every step N, centres and sides change by random "
                    "fractions in (-L, L) of N, x and b")
        ->check(in_half_open_range(0, 1))
        ->capture_default_str();
    command.add_option("-s,--steps", options.steps, "number of time steps (frames), the first included")
        ->check(at_least(1))
        ->capture_default_str();
    command.add_option("--seed", options.seed, "seed of the random generator")
        ->check(not_negative())
        ->capture_default_str();
}

}  // namespace smb::cli
