// SPDX-License-Identifier: MIT
#include "collective_checks.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "exchange.hpp"
#include "smb/errors.hpp"

namespace smb::mpi::detail {

namespace {

/// The smallest of the ids that the ranks name (each rank names its own, or none).
BoxId smallest_over_ranks(MPI_Comm comm, bool has_one, BoxId id) {
    unsigned long long value = has_one ? id : std::numeric_limits<unsigned long long>::max();
    MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
    return value;
}

/// SplitMix64's finaliser: spreads consecutive ids evenly over the ranks.
std::uint64_t mix(std::uint64_t x) noexcept {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
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

std::size_t check_ids_unique(MPI_Comm comm, std::span<const BoxId> ids) {
    int rank = 0, ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    std::vector<int> counts(static_cast<std::size_t>(ranks), 0);
    for (BoxId id : ids) ++counts[mix(id) % static_cast<std::uint64_t>(ranks)];
    std::vector<int> fill(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), fill.begin(), 0);
    std::vector<BoxId> send(ids.size());
    for (BoxId id : ids) send[static_cast<std::size_t>(fill[mix(id) % static_cast<std::uint64_t>(ranks)]++)] = id;
    std::vector<int> receive_counts;
    std::vector<BoxId> received = all_to_all(comm, send, counts, receive_counts);
    std::sort(received.begin(), received.end());
    const auto repeat = std::adjacent_find(received.begin(), received.end());
    const bool has_repeat = repeat != received.end();
    // One reduction gives both the smallest repeat and whether there is any (the largest id may
    // itself be the repeat, so the id alone cannot say).
    unsigned long long found[2] = {has_repeat ? *repeat : std::numeric_limits<unsigned long long>::max(),
                                   has_repeat ? 0ULL : 1ULL};
    MPI_Allreduce(MPI_IN_PLACE, found, 2, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
    if (found[1] == 0) {
        throw DuplicateIdError("DistributedDetector::detect: id " + std::to_string(found[0]) +
                               " is passed more than once (on one rank, or by two ranks)");
    }
    return bytes_to_others<BoxId>(counts, rank);
}

}  // namespace smb::mpi::detail
