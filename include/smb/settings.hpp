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

    /// Most pairs detect(std::vector<Pair>&) may collect (2^28 pairs are 4 GiB). Past it, it
    /// throws PairLimitError instead of exhausting memory; detect(sink) has no limit, since the
    /// caller consumes the pairs chunk by chunk. 100 000 identical boxes make 5·10^9 pairs.
    std::size_t max_pairs_held = std::size_t{1} << 28;
};

}  // namespace smb
