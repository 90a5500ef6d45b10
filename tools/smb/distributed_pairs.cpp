// SPDX-License-Identifier: MIT
#include "distributed_pairs.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "exit_status.hpp"
#include "file_streams.hpp"
#include "mpi_run.hpp"
#include "pair_csv.hpp"
#include "scene_csv.hpp"
#include "smb/mpi/distributed_detector.hpp"

namespace smb::cli {

namespace {

/// What rank 0 tells the others before each frame: a frame follows, the scene ended, or rank 0
/// failed (a malformed line, a failed write) and every rank stops.
enum FrameStatus : std::uint64_t { frame_follows, scene_ended, reader_failed };

/// A frame's rows from rank 0 to every rank, row i to rank i mod P.
template <int Dim>
void deal_rows(const io::SceneFrame<Dim>* frame, int rank, int ranks, std::vector<BoxId>& ids,
               std::vector<Box<double, Dim>>& boxes) {
    std::vector<int> counts(static_cast<std::size_t>(ranks), 0), displacements(counts.size(), 0);
    std::vector<IdRow<Dim>> rows;
    if (rank == 0) {
        const std::size_t n = frame->ids.size();
        rows.resize(n);
        for (int r = 0; r < ranks; ++r) {
            counts[static_cast<std::size_t>(r)] =
                static_cast<int>((n + static_cast<std::size_t>(ranks - 1 - r)) / static_cast<std::size_t>(ranks));
        }
        for (int r = 1; r < ranks; ++r)
            displacements[static_cast<std::size_t>(r)] =
                displacements[static_cast<std::size_t>(r - 1)] + counts[static_cast<std::size_t>(r - 1)];
        std::vector<int> fill = displacements;
        for (std::size_t i = 0; i < n; ++i) {
            rows[static_cast<std::size_t>(fill[i % static_cast<std::size_t>(ranks)]++)] =
                IdRow<Dim>{frame->ids[i], frame->boxes[i]};
        }
    }
    int mine = 0;
    MPI_Scatter(counts.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Datatype row_type = MPI_DATATYPE_NULL;
    MPI_Type_contiguous(static_cast<int>(sizeof(IdRow<Dim>)), MPI_BYTE, &row_type);
    MPI_Type_commit(&row_type);
    std::vector<IdRow<Dim>> my_rows(static_cast<std::size_t>(mine));
    MPI_Scatterv(rows.data(), counts.data(), displacements.data(), row_type, my_rows.data(), mine, row_type, 0,
                 MPI_COMM_WORLD);
    MPI_Type_free(&row_type);
    ids.resize(my_rows.size());
    boxes.resize(my_rows.size());
    for (std::size_t i = 0; i < my_rows.size(); ++i) ids[i] = my_rows[i].id, boxes[i] = my_rows[i].box;
}

/// Every rank's pairs on rank 0.
std::vector<Pair> gather_pairs(const std::vector<Pair>& mine, int rank, int ranks) {
    int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(ranks), 0), displacements(counts.size(), 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    for (int r = 1; r < ranks; ++r)
        displacements[static_cast<std::size_t>(r)] =
            displacements[static_cast<std::size_t>(r - 1)] + counts[static_cast<std::size_t>(r - 1)];
    std::vector<Pair> all(rank == 0 ? static_cast<std::size_t>(displacements.back() + counts.back()) : 0);
    MPI_Datatype pair_type = MPI_DATATYPE_NULL;
    MPI_Type_contiguous(static_cast<int>(sizeof(Pair)), MPI_BYTE, &pair_type);
    MPI_Type_commit(&pair_type);
    MPI_Gatherv(mine.data(), count, pair_type, all.data(), counts.data(), displacements.data(), pair_type, 0,
                MPI_COMM_WORLD);
    MPI_Type_free(&pair_type);
    return all;
}

template <int Dim>
void detect_every_frame(io::SceneReader* reader, io::PairWriter* writer, int rank, int ranks) {
    mpi::DistributedDetector<double, Dim> detector(MPI_COMM_WORLD);
    io::SceneFrame<Dim> frame;
    std::vector<BoxId> ids;
    std::vector<Box<double, Dim>> boxes;
    std::vector<Pair> pairs;
    std::exception_ptr failure;  // rank 0's, told to the others at the next frame's header
    for (;;) {
        std::uint64_t header[2] = {scene_ended, 0};  // status, frame number
        if (rank == 0 && failure) {
            header[0] = reader_failed;
        } else if (rank == 0) {
            try {
                header[0] = reader->read_frame(frame) ? frame_follows : scene_ended;
                header[1] = frame.number;
            } catch (...) {
                failure = std::current_exception();
                header[0] = reader_failed;
            }
        }
        MPI_Bcast(header, 2, MPI_UINT64_T, 0, MPI_COMM_WORLD);
        if (failure) std::rethrow_exception(failure);
        if (header[0] == reader_failed) throw std::runtime_error("rank 0 could not read the scene");
        if (header[0] == scene_ended) return;
        deal_rows<Dim>(rank == 0 ? &frame : nullptr, rank, ranks, ids, boxes);
        detector.detect(ids, boxes, pairs);  // bad input throws on every rank alike
        std::vector<Pair> all = gather_pairs(pairs, rank, ranks);
        if (rank == 0) {
            sort_pairs(all);
            try {
                writer->write_frame(header[1], all);
            } catch (...) {
                failure = std::current_exception();
            }
        }
    }
}

}  // namespace

int run_distributed_pairs(const std::string& input_name, const std::string& output_name) {
    MpiRun mpi_run;
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    // Rank 0 alone touches the files; a failure to open them stops every rank.
    std::optional<io::InputFile> input;
    std::optional<io::SceneReader> reader;
    std::optional<io::OutputFile> output;
    std::exception_ptr failure;
    int dimension = 0;
    if (rank == 0) {
        try {
            input.emplace(input_name);
            reader.emplace(input->stream(), input->name());
            output.emplace(output_name);
            dimension = reader->dimension();
        } catch (...) {
            failure = std::current_exception();
        }
    }
    MPI_Bcast(&dimension, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (failure) std::rethrow_exception(failure);
    if (dimension == 0) return exit_status::failure;
    try {
        std::optional<io::PairWriter> writer;
        if (rank == 0) writer.emplace(output->stream());
        if (dimension == 2) {
            detect_every_frame<2>(rank == 0 ? &*reader : nullptr, rank == 0 ? &*writer : nullptr, rank, ranks);
        } else {
            detect_every_frame<3>(rank == 0 ? &*reader : nullptr, rank == 0 ? &*writer : nullptr, rank, ranks);
        }
        if (rank == 0) writer->flush();
    } catch (const std::exception&) {
        if (rank != 0) return exit_status::failure;  // rank 0 says what went wrong
        output->throw_if_failed();
        throw;
    }
    if (rank == 0) output->commit();
    return exit_status::success;
}

}  // namespace smb::cli
