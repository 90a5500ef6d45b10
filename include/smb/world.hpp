// SPDX-License-Identifier: MIT
#pragma once
// The persistent SMB world: boxes that move between steps and the sorted lists that follow them.

#include <concepts>
#include <cstddef>
#include <functional>
#include <memory>
#include <ranges>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/box_index.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/pair.hpp"
#include "smb/pair_events.hpp"
#include "smb/periodic.hpp"
#include "smb/profile.hpp"
#include "smb/query.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb {

namespace detail {
template <std::floating_point Real, int Dim>
class WorldState;
template <std::floating_point Real, int Dim>
struct WorldQueryIndex;
}  // namespace detail

/// A set of moving axis-aligned boxes, each under a caller-chosen BoxId, and the SMB broad
/// phase over them (Li, Feng & Owen, CMAME 195 (2006) 2252-2269).
///
/// Use: insert, update and remove boxes freely between detections; detect() then reports
/// every pair of boxes that overlap (closed convention: touching boxes overlap, see
/// smb::overlaps), each pair exactly once, with Pair::a < Pair::b. The world keeps its axial
/// cuts (and, with Pipeline::paper_lists, its sorted per-axis lists) from one detection to the
/// next, so a detection after small motions costs linear time in the number of boxes.
///
/// Errors: every mutating call validates all its input first; on bad input (a box with NaN,
/// infinity or min > max; an unknown id; an id inserted twice) it throws a subclass of
/// smb::Error and leaves the world exactly as it was.
///
/// Precision: with Pipeline::persistent_cuts, a world of double boxes holds floats for its
/// passes, shifted to the middle of the scene and rounded to the nearest float, and tests again
/// on the stored doubles every pair that the floats cannot settle (boxes within a few floats of
/// touching), so the pairs are exact; floats halve the memory every pass reads. When floats
/// would not resolve the scene (more than 1/8 of the boxes thinner than 2^-14 of the scene's
/// extent on some axis, or coordinates beyond float range) it holds the doubles instead;
/// last_precision() says which. The choice is made as Detector makes it.
///
/// Determinism: the same sequence of calls gives the same pairs in the same order, whatever
/// WorldSettings::threads. The order of pairs within one detection is otherwise unspecified;
/// sort_pairs() gives (a, b) order. A cell lists its pairs in the order the detection before
/// left its boxes, so detecting again without changes reports the same pairs, and from the
/// second such detection on in the same order too.
///
/// Thread safety: a World is not synchronised. Distinct worlds may be used from distinct
/// threads; one world must not be used from two threads at once, not even for detect().
/// detect() itself may use WorldSettings::threads threads; the sink is always called from the
/// thread that called detect().
///
/// Moving: a World moves in constant time and without throwing. The world moved from is left
/// empty, holding nothing, with default settings (WorldSettings{}); every call is valid on it,
/// and it can be used again as a new world.
template <std::floating_point Real, int Dim>
class World {
public:
    using real_type = Real;
    using box_type = Box<Real, Dim>;
    static constexpr int dimension = Dim;

    explicit World(const WorldSettings& settings = {});
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Adds a box. Throws DuplicateIdError if `id` is present, InvalidBoxError if invalid.
    void insert(BoxId id, const box_type& box);
    /// Adds many boxes at once (all or none). Throws DuplicateIdError if an id is present, or
    /// named twice in `ids`.
    void insert(std::span<const BoxId> ids, std::span<const box_type> boxes);

    /// Removes a box. Throws UnknownIdError if `id` is absent.
    void remove(BoxId id);
    /// Removes many boxes at once (all or none).
    void remove(std::span<const BoxId> ids);

    /// Moves or resizes one box. Throws UnknownIdError or InvalidBoxError.
    void update(BoxId id, const box_type& box);
    /// Moves or resizes many boxes at once (all or none). An id named twice gets the last of
    /// its boxes: checking for repeats would cost a hash set on the hot path of every step.
    void update(std::span<const BoxId> ids, std::span<const box_type> boxes);

    /// Makes the world hold exactly `boxes`, box i under id i: the way array-based
    /// simulations keep their bodies. Ids below boxes.size() are updated or inserted, ids at
    /// or above it are removed. All or none.
    void assign(std::span<const box_type> boxes);

    /// Removes every box and releases the memory the world held; keeps the settings.
    void clear();

    [[nodiscard]] bool contains(BoxId id) const;
    /// The box stored under `id`; throws UnknownIdError if absent.
    [[nodiscard]] box_type box(BoxId id) const;
    [[nodiscard]] std::size_t size() const noexcept;
    [[nodiscard]] const WorldSettings& settings() const noexcept;

    /// Replaces the contents of `pairs` by every overlapping pair. Throws PairLimitError when
    /// there are more than settings().max_pairs_held pairs; whatever it throws, `pairs` holds
    /// what it held before. The pairs are collected after the old contents and moved to the
    /// front at the end: a caller who has no use for the old pairs clears `pairs` first and
    /// saves that move (its capacity is kept either way).
    DetectStats detect(std::vector<Pair>& pairs);
    /// Reports every overlapping pair to `sink`, in chunks of settings().pair_chunk_size. An
    /// exception thrown by the sink ends the detection and propagates; the world stays valid and
    /// the next detect() reports everything again.
    DetectStats detect(const PairSink& sink);
    /// detect(pairs), then `events` updated with the pairs (PairEvents::update): the pairs that
    /// began and ended since the detection before. An id removed and inserted again in between
    /// is a new box: its old pairs end and its pairs begin; clear() ends every pair. Hand the
    /// same events to every detection: the removals are forgotten by any detection. Whatever
    /// it throws, `pairs` and `events` are as they were.
    DetectStats detect(std::vector<Pair>& pairs, PairEvents& events);

    /// Periodic detection (smb/periodic.hpp, docs/periodic.md): replaces the contents of `pairs`
    /// by every pair (a, b, shift) of ids such that box a overlaps box b translated by `shift`
    /// periods (overlaps_with_shift), each pair once, a < b. Throws ArgumentError for a bad
    /// domain or while filters, static boxes or a predicate are in use (a periodic detection
    /// does not apply them), and InvalidBoxError naming the first box too large for the domain
    /// (extent not below half the period), before anything changes; PairLimitError as
    /// detect(pairs). The domain may change from one call to the next; detections with and
    /// without a domain may alternate (each switch starts the other's cuts afresh).
    DetectStats detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs);
    /// The same, then `events` updated with the (a, b) of the pairs, as detect(pairs, events):
    /// a pair whose shift changes (it crossed the domain's boundary) stays the same contact.
    DetectStats detect(const PeriodicDomain<Real, Dim>& domain, std::vector<PeriodicPair>& pairs, PairEvents& events);

    // Filters and static boxes (smb/filter.hpp, docs/filters.md). A box inserted has the
    // default filter and is not static; removing it forgets both. Once any filter differs
    // from the default, any box is static or a predicate is set, detect() takes the filtered
    // path (the persistent cuts, whatever WorldSettings::pipeline says); when none is left,
    // the next detect() returns to the default one.

    /// Sets the filter of box `id`. Throws UnknownIdError if absent.
    void set_filter(BoxId id, const Filter& filter);
    /// Sets many filters at once (all or none); an id named twice gets the last of its filters.
    void set_filter(std::span<const BoxId> ids, std::span<const Filter> filters);
    /// Gives many boxes one filter at once (all or none), as set_static(ids, is_static).
    void set_filter(std::span<const BoxId> ids, const Filter& filter);
    /// The filter of box `id`; throws UnknownIdError if absent.
    [[nodiscard]] Filter filter(BoxId id) const;
    /// Makes box `id` static (two static boxes are never paired; a static box that does not
    /// change costs close to nothing per detection) or dynamic again. A static box may still
    /// be updated or removed: exact, but the next detection indexes the statics again.
    void set_static(BoxId id, bool is_static);
    /// The same for many boxes at once (all or none).
    void set_static(std::span<const BoxId> ids, bool is_static);
    /// Whether box `id` is static; throws UnknownIdError if absent.
    [[nodiscard]] bool is_static(BoxId id) const;
    /// Sets the predicate consulted for every overlapping pair whose filter bits pass (empty:
    /// none). The world keeps a copy; it must not call the world.
    void set_pair_predicate(PairPredicate predicate);

    /// Statistics of the last detect() call.
    [[nodiscard]] const DetectStats& last_stats() const noexcept;
    /// The last detect() call's phases and pipeline counts where settings().profile is set;
    /// all zero otherwise.
    [[nodiscard]] const DetectProfile& last_profile() const noexcept;
    /// What the last detection held: floats or the doubles themselves (see Precision above).
    [[nodiscard]] HeldPrecision last_precision() const noexcept;
    /// Pairs the held floats could not settle and that were tested again on the stored boxes,
    /// in the last detection.
    [[nodiscard]] std::size_t last_retested_pairs() const noexcept;
    /// Heap bytes held by the world now (its own accounting of its arrays).
    [[nodiscard]] std::size_t bytes_held() const noexcept;

    /// Region queries and ray casts (docs/queries.md). They answer for the boxes the world holds
    /// now, with every change made so far: they use a BoxIndex over the world's boxes, rebuilt
    /// (O(N)) by the first query after a change of the boxes (insert, update, remove, assign,
    /// clear), and reused until the next one; detections, filters and statics keep it. Results
    /// and errors as BoxIndex.

    /// Each box overlapping `box`, by id.
    void query(const box_type& box, std::vector<BoxId>& out);
    /// Every (query index, id) with the box `id` overlapping queries[index], sorted by index.
    void query(std::span<const box_type> queries, std::vector<QueryHit>& out);
    /// The boxes `ray` enters: the nearest, or all sorted by (t, id) (see BoxIndex::cast_ray).
    void cast_ray(const Ray<Real, Dim>& ray, RayHits mode, std::vector<RayHit<Real>>& out);

private:
    /// The state; a moved-from world (state_ null) gets a fresh one first.
    detail::WorldState<Real, Dim>& state();
    /// The query index, rebuilt first if the boxes changed since it was built.
    const BoxIndex<Real, Dim>& query_index();

    std::unique_ptr<detail::WorldState<Real, Dim>> state_;
    /// Made by the first query: a world that is never queried holds no index.
    std::unique_ptr<detail::WorldQueryIndex<Real, Dim>> query_index_;
};

using World2f = World<float, 2>;
using World2d = World<double, 2>;
using World3f = World<float, 3>;
using World3d = World<double, 3>;

/// One-shot detection over a single static set of boxes: box i has id i.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::vector<Pair> find_overlapping_pairs(std::span<const Box<Real, Dim>> boxes,
                                                       const WorldSettings& settings = {});

/// find_overlapping_pairs over any BoxRange: the same detection, over a span of its boxes.
template <BoxRange Range>
[[nodiscard]] std::vector<Pair> find_overlapping_pairs(const Range& boxes, const WorldSettings& settings = {}) {
    using box_type = std::ranges::range_value_t<const Range>;
    return find_overlapping_pairs<typename box_type::real_type, box_type::dimension>(
        std::span<const box_type>(std::ranges::data(boxes), std::ranges::size(boxes)), settings);
}

}  // namespace smb
