// SPDX-License-Identifier: MIT
#pragma once
// Records between ranks: grouped by destination, then sent with MPI_Alltoallv (trivially
// copyable records, as one contiguous MPI type each so that the counts are records, not bytes:
// MPI's counts are ints).

#include <mpi.h>

#include <cstddef>
#include <numeric>
#include <type_traits>
#include <vector>

namespace smb::mpi::detail {

/// Sends send[displacement(r) .. + send_counts[r]) to rank r (the records grouped by
/// destination, in rank order) and puts in `received` what every rank sent here, grouped by
/// source in rank order; `receive_counts` gets how many came from each rank. `received` keeps
/// its memory from call to call (a step's exchange is about the size of the last one's).
/// Returns the bytes of the records that left this rank (the share sent to itself stays).
template <class Record>
std::size_t all_to_all(MPI_Comm comm, const std::vector<Record>& send, const std::vector<int>& send_counts,
                       std::vector<int>& receive_counts, std::vector<Record>& received) {
    static_assert(std::is_trivially_copyable_v<Record>);
    const auto ranks = send_counts.size();
    receive_counts.assign(ranks, 0);
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
    std::vector<int> send_displacements(ranks, 0), receive_displacements(ranks, 0);
    std::exclusive_scan(send_counts.begin(), send_counts.end(), send_displacements.begin(), 0);
    std::exclusive_scan(receive_counts.begin(), receive_counts.end(), receive_displacements.begin(), 0);
    const std::size_t total = ranks == 0 ? 0
                                         : static_cast<std::size_t>(receive_displacements.back()) +
                                               static_cast<std::size_t>(receive_counts.back());
    received.resize(total);
    MPI_Datatype record_type = MPI_DATATYPE_NULL;
    MPI_Type_contiguous(static_cast<int>(sizeof(Record)), MPI_BYTE, &record_type);
    MPI_Type_commit(&record_type);
    MPI_Alltoallv(send.data(), send_counts.data(), send_displacements.data(), record_type, received.data(),
                  receive_counts.data(), receive_displacements.data(), record_type, comm);
    MPI_Type_free(&record_type);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::size_t records = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
        if (static_cast<int>(r) != rank) records += static_cast<std::size_t>(send_counts[r]);
    }
    return records * sizeof(Record);
}

/// Sorts `targets`, (rank, what) each, by rank into `send` as record_of(what) (a counting sort:
/// a rank's records lie together, in the order of the targets), and counts[r] how many go to
/// rank r, ready for all_to_all.
template <class Target, class Record, class RecordOf>
void sort_by_rank(const std::vector<Target>& targets, int ranks, std::vector<Record>& send, std::vector<int>& counts,
                  RecordOf record_of) {
    counts.assign(static_cast<std::size_t>(ranks), 0);
    for (const Target& target : targets) ++counts[static_cast<std::size_t>(target.first)];
    std::vector<int> fill(counts.size(), 0);
    std::exclusive_scan(counts.begin(), counts.end(), fill.begin(), 0);
    send.resize(targets.size());
    for (const Target& target : targets)
        send[static_cast<std::size_t>(fill[static_cast<std::size_t>(target.first)]++)] = record_of(target.second);
}

}  // namespace smb::mpi::detail
