// SPDX-License-Identifier: MIT
#pragma once
// The SMB broad phase over an array of boxes the caller keeps: no ids, no copy of the input.

#include <concepts>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/candidate_pairs.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/pair.hpp"
#include "smb/pair_events.hpp"
#include "smb/periodic.hpp"
#include "smb/profile.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb {

namespace detail {
template <std::floating_point Real, int Dim>
class DetectorState;
}  // namespace detail

/// The SMB broad phase for simulations that keep their bodies' boxes in an array of their own:
/// each detect() takes the whole array, box i being body i, and reports every pair of indices
/// whose boxes overlap (closed convention, see smb::overlaps), once, with Pair::a < Pair::b.
///
/// The detector does not copy the array between calls. What it keeps is what makes the next call
/// fast: its axial cuts, and an order of the indices that follows the cells. So box i should be
/// the same body from one call to the next (a body that moved a little); the array may grow or
/// shrink between calls, and any contents give the exact pairs, only more slowly when the
/// bodies jumped. Compared with World, a Detector holds about half the memory per box (see
/// docs/performance.md) and needs no insert/update/remove calls; World suits callers who name
/// their bodies by ids that come and go.
///
/// Precision: for double boxes, the detector holds floats, shifted to the middle of the scene
/// and rounded to the nearest float, and tests again on the caller's doubles every pair that
/// the floats cannot settle (boxes within a few floats of touching), so the pairs are exact.
/// When floats would not resolve the scene (more than 1/8 of the boxes thinner than 2^-14 of
/// the scene's extent on some axis, or coordinates beyond float range) it holds doubles
/// instead; last_precision() says which. The choice is made again when the scene outgrows the region it
/// was made for, or the number of boxes changes by more than a quarter.
///
/// Skin: with DetectorSettings::skin > 0 it also keeps, between calls, each box's fat box (grown
/// by the skin), a float copy of the boxes, and the pairs of fat boxes that overlap; a call then
/// checks each box against its fat box and tests those pairs only, which pays while boxes move
/// much less than the skin per call (docs/algorithm.md, docs/performance.md "The skin").
///
/// Errors: detect() checks every box before it changes anything; a box with NaN, infinity or
/// min > max throws InvalidBoxError naming its index, and the detector and the caller's vector
/// of pairs stay as they were.
///
/// Determinism and threads: as World (DetectorSettings::threads; the sink runs on the calling
/// thread; the same calls give the same pairs in the same order whatever the thread count).
/// The array must not change while detect() runs.
///
/// Moving: a Detector moves in constant time and without throwing. The detector moved from is
/// left holding nothing, with default settings (DetectorSettings{}), as a new one; every call
/// is valid on it.
template <std::floating_point Real, int Dim>
class Detector {
public:
    using real_type = Real;
    using box_type = Box<Real, Dim>;
    static constexpr int dimension = Dim;

    explicit Detector(const DetectorSettings& settings = {});
    ~Detector();
    Detector(Detector&&) noexcept;
    Detector& operator=(Detector&&) noexcept;
    Detector(const Detector&) = delete;
    Detector& operator=(const Detector&) = delete;

    /// Replaces the contents of `pairs` by every overlapping pair of `boxes`, box i under id i.
    /// Throws PairLimitError past settings().max_pairs_held pairs; whatever it throws, `pairs`
    /// holds what it held before. The pairs are collected after the old contents and moved to
    /// the front at the end: a caller who has no use for the old pairs clears `pairs` first and
    /// saves that move (its capacity is kept either way).
    DetectStats detect(std::span<const box_type> boxes, std::vector<Pair>& pairs);
    /// Reports every overlapping pair to `sink`, in chunks of settings().pair_chunk_size. An
    /// exception thrown by the sink ends the detection and propagates; the detector stays valid.
    DetectStats detect(std::span<const box_type> boxes, const PairSink& sink);
    /// detect(boxes, pairs), then `events` updated with the pairs (PairEvents::update): the
    /// pairs of indices that began and ended since the detection before. Between two
    /// detections, tell `events` of every swap-remove (PairEvents::swap_remove) and of every
    /// new body put at an old index (PairEvents::replace); appended bodies need nothing.
    /// Whatever it throws, `pairs` and `events` are as they were.
    DetectStats detect(std::span<const box_type> boxes, std::vector<Pair>& pairs, PairEvents& events);

    /// The same detections with filters (smb/filter.hpp): a pair of indices is reported when
    /// the boxes overlap, their filters pass, they are not both static, and the predicate (if
    /// any) says yes. Each span of `filters` is empty or holds one entry per box, else
    /// ArgumentError before anything changes. Boxes whose category or mask is 0 are left out
    /// of the detection; the other filters, the static flags and the predicate are applied to
    /// the pairs it finds (a World also keeps its statics out of its detection: docs/filters.md).
    DetectStats detect(std::span<const box_type> boxes, const DetectFilters& filters, std::vector<Pair>& pairs);
    DetectStats detect(std::span<const box_type> boxes, const DetectFilters& filters, const PairSink& sink);

    /// Periodic detection (smb/periodic.hpp, docs/periodic.md): replaces the contents of `pairs`
    /// by every pair (a, b, shift) such that box a overlaps box b translated by `shift` periods
    /// (overlaps_with_shift), each pair once, a < b. Throws ArgumentError for a bad domain and
    /// InvalidBoxError for a box that is invalid or too large for it (extent not below half the
    /// period), naming its index, before anything changes. Runs its own cuts (and skin list,
    /// with a skin) beside the ordinary detection's, so calls with and without a domain may
    /// alternate on one detector; threads as the settings say.
    DetectStats detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                       std::vector<PeriodicPair>& pairs);
    /// The same, then `events` updated with the (a, b) of the pairs: a pair whose shift changes
    /// (it crossed the domain's boundary) stays the same contact.
    DetectStats detect(std::span<const box_type> boxes, const PeriodicDomain<Real, Dim>& domain,
                       std::vector<PeriodicPair>& pairs, PairEvents& events);

    /// After a detection over the whole array on the cuts (not on the skin, not split into
    /// classes by filters, not periodic): the indices of its boxes in the order the next
    /// detection reads them (cell by cell, each column in x order), every index once; empty
    /// otherwise. A caller that renumbers its bodies so that index i holds the body that was at
    /// index order[i], as DEM and molecular dynamics codes sort their particles every few
    /// hundred steps, has the following detections read its array as one stream instead of
    /// gathering every box from a random place (and its own loops over neighbours gain the same
    /// locality). Valid until the next detect(), clear(), move or destruction.
    [[nodiscard]] std::span<const std::uint32_t> suggested_order() const noexcept;
    /// Tells the detector that the caller renumbered its bodies by suggested_order(), so that
    /// the next detection reads the array in its new order at once. Without it the next
    /// detection finds every box away from where it was and takes a step or two to order them
    /// afresh, as after a jump; only speed depends on it (a call without a renumbering costs
    /// the same). Does nothing where suggested_order() is empty.
    void follow_suggested_order();

    /// Forgets the cuts and the order, and releases the memory held; keeps the settings.
    void clear();

    [[nodiscard]] const DetectorSettings& settings() const noexcept;
    /// Statistics of the last detect() call.
    [[nodiscard]] const DetectStats& last_stats() const noexcept;
    /// The last detect() call's phases and pipeline counts where settings().profile is set;
    /// all zero otherwise.
    [[nodiscard]] const DetectProfile& last_profile() const noexcept;
    /// What the last detection held: floats or a copy of the doubles.
    [[nodiscard]] HeldPrecision last_precision() const noexcept;
    /// Pairs the held floats could not settle and that were tested again on the input, in the
    /// last detection.
    [[nodiscard]] std::size_t last_retested_pairs() const noexcept;
    /// Heap bytes held by the detector now (its own accounting of its arrays); the caller's
    /// array is not counted.
    [[nodiscard]] std::size_t bytes_held() const noexcept;

    /// With a skin: the candidate pairs (the Verlet list) after the last detect(), the margin
    /// within which it holds every pair, and whether there is one (smb/candidate_pairs.hpp).
    /// The span stays valid until the next detect(), clear(), move or destruction. The first
    /// call after a detection turns the list into the caller's indices (linear in the
    /// candidates); later calls return the same. Not const for that reason, and not
    /// synchronised, as detect().
    [[nodiscard]] CandidatePairs candidates();

private:
    /// The state; a moved-from detector (state_ null) gets a fresh one first.
    detail::DetectorState<Real, Dim>& state();

    std::unique_ptr<detail::DetectorState<Real, Dim>> state_;
};

using Detector2f = Detector<float, 2>;
using Detector2d = Detector<double, 2>;
using Detector3f = Detector<float, 3>;
using Detector3d = Detector<double, 3>;

}  // namespace smb
