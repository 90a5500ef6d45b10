// SPDX-License-Identifier: MIT
#pragma once
// The ids of all ranks, spread over the ranks by a hash and kept from step to step, so that the
// duplicate check of a step sends only the ids inserted and removed since the last one.

#include <mpi.h>

#include <cstddef>
#include <span>
#include <unordered_set>
#include <vector>

#include "smb/pair.hpp"

namespace smb::mpi::detail {

class DistributedIdSet {
public:
    /// This rank's ids of the last step that passed the check, sorted.
    [[nodiscard]] std::span<const BoxId> last_ids() const noexcept { return last_ids_; }

    /// Throws DuplicateIdError on every rank, naming the smallest id that any rank passes twice
    /// or that two ranks pass, and then changes nothing; otherwise records `sorted_ids` (this
    /// rank's ids of the step, sorted) as the last ids. Each id inserted or removed since the last
    /// step travels to the rank its hash names, which holds the ids of all ranks that hash there
    /// and finds a repeat among them. Collective; returns the bytes this rank sent to others.
    std::size_t check_and_record(MPI_Comm comm, std::span<const BoxId> sorted_ids);

private:
    std::vector<BoxId> last_ids_;
    std::unordered_set<BoxId> hashed_here_;  // every rank's ids whose hash names this rank
};

}  // namespace smb::mpi::detail
