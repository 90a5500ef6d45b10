// SPDX-License-Identifier: MIT
#include "distributed_id_set.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <utility>

#include "exchange.hpp"
#include "smb/errors.hpp"

namespace smb::mpi::detail {

namespace {

/// SplitMix64's finaliser: spreads consecutive ids evenly over the ranks.
std::uint64_t mix(std::uint64_t x) noexcept {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

/// `ids` to the ranks their hash names; returns what arrived here, and adds the bytes sent.
std::vector<BoxId> send_to_hash_ranks(MPI_Comm comm, const std::vector<BoxId>& ids, int ranks,
                                      std::size_t& bytes_sent) {
    std::vector<std::pair<int, BoxId>> targets;
    targets.reserve(ids.size());
    for (BoxId id : ids) targets.push_back({static_cast<int>(mix(id) % static_cast<std::uint64_t>(ranks)), id});
    std::vector<BoxId> send, received;
    std::vector<int> counts, receive_counts;
    sort_by_rank(targets, ranks, send, counts, [](BoxId id) { return id; });
    bytes_sent += all_to_all(comm, send, counts, receive_counts, received);
    return received;
}

}  // namespace

std::size_t DistributedIdSet::check_and_record(MPI_Comm comm, std::span<const BoxId> sorted_ids) {
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    constexpr BoxId none = std::numeric_limits<BoxId>::max();
    // A repeat on this rank is found here; repeats across ranks where the hash sends them.
    const auto local_repeat = std::adjacent_find(sorted_ids.begin(), sorted_ids.end());
    BoxId smallest_repeat = local_repeat != sorted_ids.end() ? *local_repeat : none;
    bool has_repeat = local_repeat != sorted_ids.end();

    std::vector<BoxId> inserted, removed;
    std::set_difference(sorted_ids.begin(), sorted_ids.end(), last_ids_.begin(), last_ids_.end(),
                        std::back_inserter(inserted));
    std::set_difference(last_ids_.begin(), last_ids_.end(), sorted_ids.begin(), sorted_ids.end(),
                        std::back_inserter(removed));
    inserted.erase(std::unique(inserted.begin(), inserted.end()), inserted.end());
    std::size_t bytes_sent = 0;
    std::vector<BoxId> removed_here = send_to_hash_ranks(comm, removed, ranks, bytes_sent);
    std::vector<BoxId> inserted_here = send_to_hash_ranks(comm, inserted, ranks, bytes_sent);
    std::sort(removed_here.begin(), removed_here.end());
    std::sort(inserted_here.begin(), inserted_here.end());
    // An inserted id repeats when two ranks insert it, or when it is here already and its last
    // holder did not remove it.
    for (std::size_t i = 0; i < inserted_here.size(); ++i) {
        const BoxId id = inserted_here[i];
        const bool twice = i + 1 < inserted_here.size() && inserted_here[i + 1] == id;
        const bool kept_elsewhere =
            hashed_here_.count(id) != 0 && !std::binary_search(removed_here.begin(), removed_here.end(), id);
        if (twice || kept_elsewhere) {
            smallest_repeat = std::min(smallest_repeat, id);
            has_repeat = true;
            break;  // sorted: the first is the smallest here
        }
    }
    // One reduction gives both the smallest repeat and whether there is any (the largest id may
    // itself be the repeat, so the id alone cannot say).
    unsigned long long found[2] = {smallest_repeat, has_repeat ? 0ULL : 1ULL};
    MPI_Allreduce(MPI_IN_PLACE, found, 2, MPI_UNSIGNED_LONG_LONG, MPI_MIN, comm);
    if (found[1] == 0) {
        throw DuplicateIdError("DistributedDetector::detect: id " + std::to_string(found[0]) +
                               " is passed more than once (on one rank, or by two ranks)");
    }
    for (BoxId id : removed_here) hashed_here_.erase(id);
    hashed_here_.insert(inserted_here.begin(), inserted_here.end());
    last_ids_.assign(sorted_ids.begin(), sorted_ids.end());
    return bytes_sent;
}

}  // namespace smb::mpi::detail
