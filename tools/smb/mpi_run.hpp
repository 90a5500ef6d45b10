// SPDX-License-Identifier: MIT
#pragma once
// MPI for the length of a distributed command (unless the caller had started it already).

#include <mpi.h>

#include "smb/box.hpp"

namespace smb::cli {

/// A box and its id as one record, the unit the distributed commands send between ranks.
template <int Dim>
struct IdRow {
    BoxId id;
    Box<double, Dim> box;
};

class MpiRun {
public:
    MpiRun() {
        int started = 0;
        MPI_Initialized(&started);
        if (!started) {
            MPI_Init(nullptr, nullptr);
            owns_ = true;
        }
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    }
    ~MpiRun() {
        if (owns_) MPI_Finalize();
    }
    MpiRun(const MpiRun&) = delete;
    MpiRun& operator=(const MpiRun&) = delete;

    [[nodiscard]] int rank() const noexcept { return rank_; }
    [[nodiscard]] int ranks() const noexcept { return ranks_; }

private:
    bool owns_ = false;
    int rank_ = 0;
    int ranks_ = 1;
};

}  // namespace smb::cli
