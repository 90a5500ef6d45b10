// SPDX-License-Identifier: MIT
#pragma once
// The checks of every rank's input that all ranks agree on before any exchange, so that bad
// input anywhere makes every rank throw the same error instead of leaving some in a collective.

#include <mpi.h>

#include <cstddef>
#include <span>

#include "smb/pair.hpp"

namespace smb::mpi::detail {

/// What each rank found in its own input, to be summed over the ranks.
struct LocalInputFindings {
    bool lengths_differ = false;    ///< ids and boxes of different lengths
    bool has_invalid_box = false;   ///< a box with NaN, infinity or min > max
    BoxId smallest_invalid_id = 0;  ///< the smallest id of such a box
    bool ids_changed = false;       ///< the ids differ from the last step's
};

/// What the ranks found together.
struct GlobalInputFindings {
    bool ids_changed_anywhere = false;
    unsigned long long total_boxes = 0;
};

/// Sums the findings (and `region_counts`, in place, in the same reduction) over the ranks, and
/// throws on every rank, with the same message, ArgumentError or InvalidBoxError when any
/// rank's input was bad. Collective.
GlobalInputFindings agree_on_input(MPI_Comm comm, const LocalInputFindings& local, std::size_t local_boxes,
                                   std::span<unsigned long long> region_counts);

}  // namespace smb::mpi::detail
