#pragma once

#include <cstddef>

namespace smb {

/// Tuning of a World. Every field has a default that suits the paper's workloads; a
/// default-constructed WorldSettings is the recommended start.
struct WorldSettings {
    /// Number of boxes the axial cut aims to put in one cell. The number of cuts per axis is
    /// derived from it: about (N / target_cell_population)^(1/Dim) segments on each axis.
    std::size_t target_cell_population = 24;

    /// Number of pairs handed to a PairSink in one call of detect(sink).
    std::size_t pair_chunk_size = 4096;
};

}  // namespace smb
