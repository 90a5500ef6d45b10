// SPDX-License-Identifier: MIT
#pragma once
// `smb run --distributed`: the paper's environment, each rank generating its own share
// (workload::EnvironmentShare), detected by smb::mpi::DistributedDetector over the ranks of
// MPI_COMM_WORLD (run under mpirun).

#include <cstddef>
#include <string>

#include "environment_options.hpp"

namespace smb::cli {

struct DistributedRunOptions {
    std::size_t target_cell_population = 0;
    std::size_t threads = 1;
    std::size_t check_every = 0;
    bool check = true;
    bool json = false;
    std::string pair_counts;  ///< where to write the pairs of every step; empty: nowhere
};

/// Rank r holds the boxes whose id mod P is r. The summary on rank 0's standard output has the
/// serial command's heading, pairs and check lines (the check runs the grid reference over the
/// shares passed around a ring: ring_reference.hpp), and the pair counts file the serial
/// command's bytes. Initialises and finalises MPI. Every rank returns the same exit status;
/// rank 0 alone reports an error, the others return exit_status::failure quietly.
int run_distributed_environment(const EnvironmentOptions& environment, const DistributedRunOptions& options);

}  // namespace smb::cli
