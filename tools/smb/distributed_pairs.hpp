// SPDX-License-Identifier: MIT
#pragma once
// `smb pairs --distributed`: the pairs of every frame found by smb::mpi::DistributedDetector
// over the ranks of MPI_COMM_WORLD (run under mpirun), written as the serial command writes them.

#include <string>

namespace smb::cli {

/// Rank 0 reads the scene and deals each frame's rows round-robin over the ranks (so the
/// distribution says nothing about space); the ranks detect together; rank 0 gathers the pairs,
/// sorts them and writes the pair CSV. Initialises and finalises MPI. Returns the exit status
/// on every rank; rank 0 alone throws what the serial command would (and says it), the other
/// ranks return exit_status::failure quietly.
int run_distributed_pairs(const std::string& input_name, const std::string& output_name);

}  // namespace smb::cli
