// SPDX-License-Identifier: MIT
#pragma once
// What the distributed tests share: a global scene every rank builds alike (a test may hold all
// boxes; the detector must not), the brute-force pairs, and the gathering of every rank's pairs.

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::mpi::test {

inline int rank_of(MPI_Comm comm = MPI_COMM_WORLD) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    return rank;
}

inline int ranks_of(MPI_Comm comm = MPI_COMM_WORLD) {
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    return ranks;
}

/// Boxes under ids, the same on every rank, with the rank that holds each.
template <class BoxT>
struct Scene {
    std::vector<BoxId> ids;
    std::vector<BoxT> boxes;
    std::vector<int> holders;

    /// The ids and boxes this rank holds, in scene order.
    void share_of(int rank, std::vector<BoxId>& my_ids, std::vector<BoxT>& my_boxes) const {
        my_ids.clear();
        my_boxes.clear();
        for (std::size_t i = 0; i < ids.size(); ++i) {
            if (holders[i] == rank) {
                my_ids.push_back(ids[i]);
                my_boxes.push_back(boxes[i]);
            }
        }
    }

    [[nodiscard]] int holder_of(BoxId id) const {
        const auto at = std::find(ids.begin(), ids.end(), id);
        return at == ids.end() ? -1 : holders[static_cast<std::size_t>(at - ids.begin())];
    }
};

/// Every overlapping pair by brute force, (smaller id, larger id), sorted.
template <class BoxT>
std::vector<Pair> brute_force_pairs(const Scene<BoxT>& scene) {
    std::vector<Pair> pairs;
    for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
        for (std::size_t j = i + 1; j < scene.boxes.size(); ++j) {
            if (overlaps(scene.boxes[i], scene.boxes[j])) {
                pairs.push_back({std::min(scene.ids[i], scene.ids[j]), std::max(scene.ids[i], scene.ids[j])});
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

/// A pair as one rank received it.
struct RankedPair {
    Pair pair;
    int rank;
    friend auto operator<=>(const RankedPair&, const RankedPair&) = default;
};

/// Every rank's pairs, with the rank that received each, sorted: on every rank alike.
inline std::vector<RankedPair> gather_pairs(const std::vector<Pair>& mine) {
    std::vector<RankedPair> tagged;
    for (const Pair& pair : mine) tagged.push_back({pair, rank_of()});
    const int ranks = ranks_of();
    int my_bytes = static_cast<int>(tagged.size() * sizeof(RankedPair));
    std::vector<int> bytes(static_cast<std::size_t>(ranks));
    MPI_Allgather(&my_bytes, 1, MPI_INT, bytes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::vector<int> displacements(bytes.size(), 0);
    for (std::size_t r = 1; r < bytes.size(); ++r) displacements[r] = displacements[r - 1] + bytes[r - 1];
    std::vector<RankedPair> all(static_cast<std::size_t>(displacements.back() + bytes.back()) / sizeof(RankedPair));
    MPI_Allgatherv(tagged.data(), my_bytes, MPI_BYTE, all.data(), bytes.data(), displacements.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    std::sort(all.begin(), all.end());
    return all;
}

/// A random box of side up to `size` inside the unit cube (or square), on an engine that every
/// rank seeds alike.
template <class BoxT>
BoxT random_box(std::mt19937_64& engine, double size) {
    using Real = typename BoxT::real_type;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    BoxT box;
    for (int k = 0; k < BoxT::dimension; ++k) {
        const double low = unit(engine);
        box.min[k] = static_cast<Real>(low);
        box.max[k] = static_cast<Real>(low + size * unit(engine));
    }
    return box;
}

}  // namespace smb::mpi::test
