// SPDX-License-Identifier: MIT
#include "collective_checks.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "smb/errors.hpp"

namespace smb::mpi::detail {

namespace {

/// The smallest of the ids that the ranks name (each rank names its own, or none).
BoxId smallest_over_ranks(MPI_Comm comm, bool has_one, BoxId id) {
    unsigned long long value = has_one ? id : std::numeric_limits<unsigned long long>::max();
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
    return value;
}

}  // namespace

GlobalInputFindings agree_on_input(MPI_Comm comm, const LocalInputFindings& local, std::size_t local_boxes,
                                   std::span<unsigned long long> region_counts) {
    enum : std::size_t { lengths_differ, invalid_box, ids_changed, total_boxes, header };
    std::vector<unsigned long long> sums(header + region_counts.size(), 0);
    sums[lengths_differ] = local.lengths_differ ? 1 : 0;
    sums[invalid_box] = local.has_invalid_box ? 1 : 0;
    sums[ids_changed] = local.ids_changed ? 1 : 0;
    sums[total_boxes] = local_boxes;
    std::copy(region_counts.begin(), region_counts.end(), sums.begin() + header);
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
    if (sums[lengths_differ] != 0) {
        throw ArgumentError("DistributedDetector::detect: ids and boxes differ in length on " +
                            std::to_string(sums[lengths_differ]) + " rank(s)");
    }
    if (sums[invalid_box] != 0) {
        const BoxId id = smallest_over_ranks(comm, local.has_invalid_box, local.smallest_invalid_id);
        throw InvalidBoxError("DistributedDetector::detect: box " + std::to_string(id) +
                              " is invalid (a NaN or infinite coordinate, or min > max); " +
                              std::to_string(sums[invalid_box]) + " rank(s) hold invalid boxes");
    }
    std::copy(sums.begin() + header, sums.end(), region_counts.begin());
    return {sums[ids_changed] != 0, sums[total_boxes]};
}

}  // namespace smb::mpi::detail
