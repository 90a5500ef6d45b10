#include "environment_options.hpp"

namespace smb::cli {

workload::EnvironmentParams EnvironmentOptions::params() const {
    workload::EnvironmentParams params;
    params.box_count = box_count;
    params.packing_density = packing_density;
    if (side_option != nullptr && side_option->count() > 0) params.cube_side = cube_side;
    params.size_ratio = size_ratio;
    params.update_factor = update_factor;
    params.seed = seed;
    return params;
}

void add_environment_options(CLI::App& command, EnvironmentOptions& options) {
    command.add_option("--dim", options.dimension, "dimension of the boxes")
        ->check(CLI::IsMember({2, 3}))
        ->capture_default_str();
    command.add_option("-n,--boxes", options.box_count, "number of boxes N at the first step")
        ->capture_default_str();
    auto* density =
        command
            .add_option("-E,--density", options.packing_density,
                        "packing density E = N((a+b)/2)^dim / x^dim; sets the cube side x")
            ->check(CLI::PositiveNumber)
            ->capture_default_str();
    options.side_option = command
                              .add_option("--side", options.cube_side,
                                          "cube side x instead of --density (E is then derived)")
                              ->check(CLI::PositiveNumber)
                              ->excludes(density);
    command
        .add_option("-H,--size-ratio", options.size_ratio,
                    "size ratio H = b/a of the largest to the smallest side (b = 1)")
        ->check(CLI::Range(1.0, 1e12))
        ->capture_default_str();
    command
        .add_option("-L,--update-factor", options.update_factor,
                    "update factor: every step N, centres and sides change by random "
                    "fractions in (-L, L) of N, x and b")
        ->check(CLI::Range(0.0, 0.999999))
        ->capture_default_str();
    command
        .add_option("-s,--steps", options.steps,
                    "number of time steps (frames), the first included")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command.add_option("--seed", options.seed, "seed of the random generator")
        ->capture_default_str();
}

}  // namespace smb::cli
