// SPDX-License-Identifier: MIT
#include "ring_reference.hpp"

#include <cstdint>

#include "mpi_run.hpp"
#include "smb/workload/reference_grid.hpp"

namespace smb::cli {

namespace {

/// Sends `rows` to rank + 1 and returns what rank - 1 sent. Collective over the ring.
template <int Dim>
std::vector<IdRow<Dim>> pass_along(MPI_Comm comm, const std::vector<IdRow<Dim>>& rows, int rank, int ranks) {
    const int next = (rank + 1) % ranks;
    const int previous = (rank + ranks - 1) % ranks;
    std::uint64_t count = rows.size();
    std::uint64_t incoming = 0;
    MPI_Sendrecv(&count, 1, MPI_UINT64_T, next, 0, &incoming, 1, MPI_UINT64_T, previous, 0, comm, MPI_STATUS_IGNORE);
    std::vector<IdRow<Dim>> received(incoming);
    MPI_Datatype row_type = MPI_DATATYPE_NULL;
    MPI_Type_contiguous(static_cast<int>(sizeof(IdRow<Dim>)), MPI_BYTE, &row_type);
    MPI_Type_commit(&row_type);
    MPI_Sendrecv(rows.data(), static_cast<int>(count), row_type, next, 1, received.data(), static_cast<int>(incoming),
                 row_type, previous, 1, comm, MPI_STATUS_IGNORE);
    MPI_Type_free(&row_type);
    return received;
}

}  // namespace

template <int Dim>
std::vector<Pair> ring_reference_pairs(MPI_Comm comm, std::span<const BoxId> ids,
                                       std::span<const Box<double, Dim>> boxes) {
    int rank = 0, ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks);
    std::vector<Pair> pairs = workload::grid_pairs<double, Dim>(ids, boxes);
    std::vector<IdRow<Dim>> visiting(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) visiting[i] = {ids[i], boxes[i]};
    std::vector<BoxId> both_ids;
    std::vector<Box<double, Dim>> both_boxes;
    const auto holder = [ranks](BoxId id) { return static_cast<int>(id % static_cast<BoxId>(ranks)); };
    for (int round = 1; round < ranks; ++round) {
        visiting = pass_along<Dim>(comm, visiting, rank, ranks);
        const int source = (rank + ranks - round) % ranks;
        both_ids.assign(ids.begin(), ids.end());
        both_boxes.assign(boxes.begin(), boxes.end());
        for (const IdRow<Dim>& row : visiting) {
            both_ids.push_back(row.id);
            both_boxes.push_back(row.box);
        }
        // The grid finds the pairs inside each share again; only those across are new here.
        for (const Pair& pair : workload::grid_pairs<double, Dim>(both_ids, both_boxes)) {
            if (holder(pair.a) == rank && holder(pair.b) == source) pairs.push_back(pair);
        }
    }
    sort_pairs(pairs);
    return pairs;
}

template std::vector<Pair> ring_reference_pairs<2>(MPI_Comm, std::span<const BoxId>, std::span<const Box<double, 2>>);
template std::vector<Pair> ring_reference_pairs<3>(MPI_Comm, std::span<const BoxId>, std::span<const Box<double, 3>>);

}  // namespace smb::cli
