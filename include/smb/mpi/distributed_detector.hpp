// SPDX-License-Identifier: MIT
#pragma once
// The SMB broad phase over boxes spread across the ranks of an MPI communicator: a domain
// decomposition by axial cuts of equal population, and smb's own Detector inside each region.

#include <mpi.h>

#include <concepts>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"

namespace smb::mpi {

/// Which rank receives a pair found by the distributed detection.
enum class PairHandOff {
    /// The rank that passed in the box with the smaller id (Pair::a): each pair on one rank.
    smaller_id_holder,
    /// Both ranks that passed in its boxes: once on each, and once only where one rank holds
    /// both. For codes that apply a contact to each body on the rank that holds it.
    both_holders,
};

/// Tuning of a DistributedDetector.
struct DistributedSettings {
    /// Who receives each pair.
    PairHandOff hand_off = PairHandOff::smaller_id_holder;
    /// The regions are cut again when the most populated holds more than this many times the
    /// mean population (boxes counted by their centre). At least 1; the cuts are kept while the
    /// population stays within it, so that a step after small motions reuses them.
    double rebalance_threshold = 1.25;
    /// The settings of the Detector each rank runs inside its region.
    DetectorSettings detector{};
};

/// What one distributed detect() did on this rank; the byte counts are what this rank sent.
struct DistributedStats {
    std::size_t boxes_passed = 0;     ///< boxes this rank passed in
    std::size_t boxes_in_region = 0;  ///< boxes this rank received for its region, ghosts included
    std::size_t boxes_owned = 0;      ///< of those, the boxes whose centre lies in the region
    std::size_t pairs_found = 0;      ///< pairs this rank's region kept (each pair in one region)
    std::size_t pairs_received = 0;   ///< pairs handed to this rank (the size of the result)
    std::size_t box_bytes_sent = 0;   ///< bytes of boxes (id and coordinates) sent to the regions
    std::size_t pair_bytes_sent = 0;  ///< bytes of pairs sent to their holders
    std::size_t id_bytes_sent = 0;    ///< bytes of ids sent for the duplicate check (0 when no id set changed)
    bool recut = false;               ///< whether the regions were cut again this step
    double imbalance = 0;             ///< largest region population over the mean, before any recut
    double total_seconds = 0;         ///< wall-clock seconds of the call on this rank
    double local_detect_seconds = 0;  ///< of which the Detector inside the region
};

namespace detail {
template <std::floating_point Real, int Dim>
class DistributedState;
}  // namespace detail

/// Every overlapping pair of the boxes that all ranks of a communicator hold together.
///
/// Use: every rank constructs one on the same communicator, then at each step every rank calls
/// detect() with the boxes it holds, each under a global 64-bit id (any distribution of the
/// boxes over the ranks; a rank may hold none). The ranks together find every pair of boxes
/// that overlap (closed convention, as smb::overlaps), each exactly once, and hand it to the
/// rank that holds the box with the smaller id (or to both holders, DistributedSettings::
/// hand_off), as Pair{a, b} with a < b. detect() is collective: every rank of the communicator
/// must call it, and none returns before all have called it.
///
/// How: the space is cut into one region per rank by axial cuts of equal population (the
/// ranks' count factored over the axes; the first axis cut into slabs, each slab on the next
/// axis, ...), found by bisection with MPI_Allreduce of counts: no rank gathers the boxes. Each
/// box travels to every region it overlaps (MPI_Alltoallv), and after that only when it moved,
/// left or entered a region, vanished or passed to another rank: each region keeps the boxes it
/// received between steps, until the regions are cut again. Each rank runs a persistent
/// smb::Detector over its region's boxes and keeps a pair only when the lower corner of the two
/// boxes' intersection lies in its region (regions are half-open, [lower, upper) on each
/// axis), so every pair is kept by exactly one region. The pairs then travel to their holders.
/// The cuts persist between steps and are recomputed only when the imbalance passes
/// DistributedSettings::rebalance_threshold. docs/distributed.md says what is sent each step.
///
/// Errors: before any exchange, the ranks agree collectively on the input's validity, so bad
/// input on any rank makes every rank throw the same exception, with the same message, and none
/// hangs: ArgumentError (ids and boxes of different lengths), InvalidBoxError (NaN, infinity
/// or min > max; the smallest such id is named), DuplicateIdError (an id passed twice, on one
/// rank or on two; the smallest is named). The detector stays valid; `pairs` stays as it was.
///
/// Memory: a rank holds its own boxes' ids, coordinates and regions as last sent, its region's
/// boxes (its share and the ghosts), the ids of all ranks that hash to it (about N/P, for the
/// duplicate check) and its pairs; never all boxes. Counts per rank and per message must stay below 2^31 (MPI's int).
///
/// Thread safety: as smb::Detector; MPI must be initialised (any thread level) and not
/// finalised while the detector is used. The communicator is duplicated, so the detector's
/// messages never mix with the caller's.
template <std::floating_point Real, int Dim>
class DistributedDetector {
public:
    using real_type = Real;
    using box_type = Box<Real, Dim>;
    static constexpr int dimension = Dim;

    /// Collective over `comm`.
    explicit DistributedDetector(MPI_Comm comm, const DistributedSettings& settings = {});
    /// Collective over the communicator (it frees its duplicate).
    ~DistributedDetector();
    DistributedDetector(const DistributedDetector&) = delete;
    DistributedDetector& operator=(const DistributedDetector&) = delete;

    /// Replaces the contents of `pairs` by the pairs handed to this rank. Collective.
    void detect(std::span<const BoxId> ids, std::span<const box_type> boxes, std::vector<Pair>& pairs);

    [[nodiscard]] const DistributedSettings& settings() const noexcept;
    [[nodiscard]] const DistributedStats& last_stats() const noexcept;
    /// The number of regions along each axis (their product is the number of ranks).
    [[nodiscard]] std::vector<int> regions_per_axis() const;
    /// This rank's region: [lower[k], upper[k]) on each axis k (infinite at the outer faces).
    [[nodiscard]] Box<double, Dim> region() const;

private:
    std::unique_ptr<detail::DistributedState<Real, Dim>> state_;
};

using DistributedDetector2f = DistributedDetector<float, 2>;
using DistributedDetector2d = DistributedDetector<double, 2>;
using DistributedDetector3f = DistributedDetector<float, 3>;
using DistributedDetector3d = DistributedDetector<double, 3>;

}  // namespace smb::mpi
