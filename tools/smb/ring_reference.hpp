// SPDX-License-Identifier: MIT
#pragma once
// The grid reference of `smb run` for a scene spread over MPI ranks, with no rank holding more
// than two shares: the shares travel around a ring, one at a time.

#include <mpi.h>

#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::cli {

/// Every overlapping pair whose smaller id is one of this rank's, sorted, when rank r of `comm`
/// holds exactly the ids whose id mod P is r (the shares of workload::EnvironmentShare). Each
/// rank runs workload::grid_pairs over its own boxes, then P - 1 times over its own and the
/// share of another rank passed along the ring (rank r sends to r + 1): it holds at most two
/// shares and computes about twice the whole scene's grid. Independent of smb::mpi's regions
/// and routing. Collective.
template <int Dim>
[[nodiscard]] std::vector<Pair> ring_reference_pairs(MPI_Comm comm, std::span<const BoxId> ids,
                                                     std::span<const Box<double, Dim>> boxes);

}  // namespace smb::cli
