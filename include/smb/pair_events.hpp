// SPDX-License-Identifier: MIT
#pragma once
// Contact events: the pairs that began and ended overlapping between two detections.

#include <cstddef>
#include <memory>
#include <span>

#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb {

namespace detail {
class PairEventsState;
}  // namespace detail

/// The pairs that began and the pairs that ended overlapping since the previous detection.
/// The caller keeps one PairEvents beside its World or Detector and hands it to every
/// detection (World::detect(pairs, events), Detector::detect(boxes, pairs, events)); it also
/// works alone, on the full pair list of any source (update()).
///
/// After an update, begun() holds the pairs of this list that were not in the previous one and
/// ended() the pairs of the previous list that are not in this one, each sorted by (a, b).
/// The first update after construction or clear() reports every pair as begun.
///
/// Bodies are named as the pairs name them: ids for a World, indices for a Detector. begun()
/// names them as this update's list does; ended() as the previous list did, so that an ended
/// pair is exactly a pair the caller was given before, even where indices have moved since.
///
/// A new body under an old name: replace(name) says that the body now under `name` is not the
/// one the previous list named so: its previous pairs end and its pairs now begin, even those
/// with the same partner. World::detect calls it for every id removed and inserted again
/// between two detections. For arrays kept by swap-remove (Detector), swap_remove(removed,
/// last) says that the body at `removed` is gone (its pairs end) and the body at `last` now
/// sits at `removed` (its pairs go on under the new index: no event). Any number of these calls
/// may come between two updates; they compose in the order made, each naming bodies by the
/// indices of the array at the time of the call. Bodies appended to the array need no call.
///
/// Cost: linear in the pairs of the two lists (they are hashed into partitions small enough for
/// the cache and compared partition by partition), plus sorting the events (docs/events.md). It
/// holds about 65 bytes per pair: the previous list, hashed, room for the next, and the events.
///
/// Threads: an update uses the threads given at construction, whatever the detection uses.
///
/// Errors: update() throws ArgumentError for a pair with a >= b or a pair listed twice, and
/// swap_remove() for removed > last; nothing changes then. A PairEvents is not synchronised.
class PairEvents {
public:
    /// `threads`: the threads an update may use (OpenMP; 0 for all cores, as
    /// DetectionSettings::threads); the events do not depend on it.
    explicit PairEvents(unsigned threads = 1);
    ~PairEvents();
    PairEvents(PairEvents&&) noexcept;
    PairEvents& operator=(PairEvents&&) noexcept;
    PairEvents(const PairEvents&) = delete;
    PairEvents& operator=(const PairEvents&) = delete;

    /// Compares `pairs` (every overlapping pair now, each once, a < b, any order) with the list
    /// of the previous update, taking the replace() and swap_remove() calls made since into
    /// account, and keeps `pairs` for the next update. All or nothing.
    void update(std::span<const Pair> pairs);
    /// As replace(name) for every name of `replaced`, then update(pairs), all or nothing.
    void update(std::span<const Pair> pairs, std::span<const BoxId> replaced);

    /// The body now under `name` is a new one: at the next update its previous pairs end and
    /// its pairs begin.
    void replace(BoxId name);
    /// Every body is a new one: at the next update every previous pair ends and every pair
    /// begins (World::clear() between two detections).
    void replace_all();
    /// The array was swap-removed: the body at `removed` is gone and the body at `last` moved to
    /// `removed` (removed == last: the last body was popped). Throws ArgumentError if
    /// removed > last.
    void swap_remove(BoxId removed, BoxId last);

    /// Pairs of the last update's list that were not in the list before, sorted by (a, b).
    [[nodiscard]] std::span<const Pair> begun() const noexcept;
    /// Pairs of the list before the last update that are not in it, sorted by (a, b), named as
    /// that list named them.
    [[nodiscard]] std::span<const Pair> ended() const noexcept;
    /// Pairs in the last update's list.
    [[nodiscard]] std::size_t size() const noexcept;

    /// Forgets the previous list, the events and the calls made since: the next update reports
    /// every pair as begun. Releases the memory held.
    void clear();
    /// The threads an update may use, as constructed (1 for a moved-from PairEvents).
    [[nodiscard]] unsigned threads() const noexcept;
    /// Heap bytes held now.
    [[nodiscard]] std::size_t bytes_held() const noexcept;

private:
    detail::PairEventsState& state();

    std::unique_ptr<detail::PairEventsState> state_;
};

}  // namespace smb
