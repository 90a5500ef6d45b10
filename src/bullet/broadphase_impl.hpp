// SPDX-License-Identifier: MIT
#pragma once
// The state of smb::bullet::Broadphase behind its public interface (its proxies and the helpers
// on their boxes), which hands its calls over one to one to broadphase.cpp (proxies, the step),
// skin.cpp (fat boxes, the cache's pairs), incremental.cpp (candidates between detections) and
// queries.cpp.

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "smb/box.hpp"
#include "smb/box_index.hpp"
#include "smb/bullet/broadphase.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"
#include "smb/world.hpp"

namespace smb::bullet {

namespace detail {
/// UnknownIdError, out of the way of the calls that check their proxy.
[[noreturn]] void throw_unknown_proxy();

/// marks_: the id is listed in fresh_, in stale_, in moved_, in changed_ids_; its proxy is alive.
inline constexpr std::uint8_t fresh_mark = 1;
inline constexpr std::uint8_t stale_mark = 2;
inline constexpr std::uint8_t moved_mark = 4;
inline constexpr std::uint8_t changed_mark = 8;
inline constexpr std::uint8_t alive_mark = 16;

/// smb::overlaps without an early exit: the passes over the candidates meet pairs apart along
/// any axis, in no order a branch predictor learns. The boxes hold no NaN (checked_box), so
/// `<=` says what `!(>)` says.
[[nodiscard]] inline bool overlaps_branchless(const Box<float, 3>& a, const Box<float, 3>& b) noexcept {
    return static_cast<bool>(static_cast<int>(a.min[0] <= b.max[0]) & static_cast<int>(b.min[0] <= a.max[0]) &
                             static_cast<int>(a.min[1] <= b.max[1]) & static_cast<int>(b.min[1] <= a.max[1]) &
                             static_cast<int>(a.min[2] <= b.max[2]) & static_cast<int>(b.min[2] <= a.max[2]));
}

/// Static and kinematic objects as btCollisionWorld files them (group StaticFilter, mask every bit
/// but StaticFilter), and any proxy whose group holds only StaticFilter and KinematicFilter bits
/// and whose mask holds neither. For any two such proxies a and b, a.group & b.mask is 0 or
/// b.group & a.mask is 0, so Bullet never pairs them and smb may hold both as static boxes.
[[nodiscard]] inline bool is_static_class(int group, int mask) noexcept {
    constexpr int fixed = btBroadphaseProxy::StaticFilter | btBroadphaseProxy::KinematicFilter;
    if (group == btBroadphaseProxy::StaticFilter) return (mask & btBroadphaseProxy::StaticFilter) == 0;
    return group != 0 && (group & ~fixed) == 0 && (mask & fixed) == 0;
}

[[nodiscard]] inline Filter filter_of(int group, int mask) noexcept {
    return Filter{static_cast<std::uint32_t>(group), static_cast<std::uint32_t>(mask)};
}

[[nodiscard]] inline Box<float, 3> box_of(const btVector3& min, const btVector3& max) noexcept {
    return Box<float, 3>{{min.x(), min.y(), min.z()}, {max.x(), max.y(), max.z()}};
}

/// The box grown by `skin` on every side. Rounding is monotone, so it holds the box.
[[nodiscard]] inline Box<float, 3> grown(const Box<float, 3>& box, float skin) noexcept {
    Box<float, 3> fat = box;
    for (int k = 0; k < 3; ++k) {
        fat.min[k] -= skin;
        fat.max[k] += skin;
    }
    return fat;
}

[[nodiscard]] inline bool contains(const Box<float, 3>& outer, const Box<float, 3>& inner) noexcept {
    for (int k = 0; k < 3; ++k) {
        if (inner.min[k] < outer.min[k] || inner.max[k] > outer.max[k]) return false;
    }
    return true;
}

inline void erase_partner(std::vector<std::uint32_t>& partners, std::uint32_t id) {
    const auto at = std::find(partners.begin(), partners.end(), id);
    if (at == partners.end()) return;
    *at = partners.back();
    partners.pop_back();
}

/// The box, or InvalidBoxError naming `what` when it has NaN, infinity or min > max.
[[nodiscard]] Box<float, 3> checked_box(const btVector3& min, const btVector3& max, const char* what);

}  // namespace detail

/// The state of the proxies, their candidates and the step's scratch that resetPool drops once
/// no proxy is left: value-reset in one, so that a member added here cannot be missed.
struct BroadphasePool {
    /// What the cache holds of a candidate: nothing (its boxes are apart), the pair, or nothing
    /// because the cache refused the pair when the boxes began to overlap (asked again when they
    /// next begin to).
    enum class Held : std::uint8_t { apart, held, refused };
    /// A pair of proxies whose fat boxes overlap (a < b).
    struct Candidate {
        std::uint32_t a = 0;
        std::uint32_t b = 0;
        Held held = Held::apart;
    };

    /// The pairs of fat boxes of the last detection as keys (src/core/pair_key_sort.hpp), sorted
    /// before the merge, and the room their radix sort works in.
    std::vector<std::uint64_t> pair_keys_;
    std::vector<std::uint64_t> key_spare_;
    std::vector<std::uint32_t> key_counts_;
    /// By id: each proxy's box (empty, pairing with nothing, once destroyed) and its fat box.
    std::vector<Box<float, 3>> boxes_;
    std::vector<Box<float, 3>> fat_boxes_;
    /// By id: the step at which the fat box was set (steps count calculateOverlappingPairs).
    std::vector<std::uint32_t> fat_since_;
    /// By id: the filter smb holds for the proxy's box (the default while the cache has a filter
    /// callback).
    std::vector<Filter> filters_;
    /// Sorted by (a, b): the pairs of fat boxes of smb's last detection.
    std::vector<Candidate> candidates_;
    std::vector<Candidate> merged_;
    std::vector<Candidate> found_;
    std::vector<std::uint8_t> found_seen_;
    /// The candidates are in (a, b) order; those found between detections are appended.
    bool candidates_sorted_ = true;
    /// The fat boxes of the live proxies as they were when it was built; the stale ones (whose
    /// fat box changed since) are listed in stale_.
    BoxIndex<float, 3> index_;
    bool index_current_ = false;
    std::vector<BoxId> index_ids_;
    std::vector<Box<float, 3>> index_boxes_;
    std::vector<BoxId> hits_;
    /// Ids whose fat box changed since the last calculateOverlappingPairs, and since index_ was
    /// built.
    std::vector<std::uint32_t> fresh_;
    std::vector<std::uint32_t> stale_;
    std::vector<Box<float, 3>> stale_boxes_;
    /// By id: the lists it is in, and whether its proxy is alive (detail::fresh_mark and others).
    std::vector<std::uint8_t> marks_;
    /// Ids whose box changed (or that were created or destroyed) since the last
    /// calculateOverlappingPairs: only the candidates they are part of are tested.
    std::vector<std::uint32_t> changed_ids_;
    std::vector<std::uint32_t> free_ids_;
    /// Ids destroyed since the last detection: not given out again before it, so that a pair of
    /// ids names the same two proxies in the candidates and in the detection's pairs.
    std::vector<std::uint32_t> retired_ids_;
    std::vector<std::uint32_t> moved_;
    std::vector<BoxId> move_ids_;
    std::vector<Box<float, 3>> move_boxes_;
    /// Static-class proxies held dynamic because they moved lately.
    std::vector<std::uint32_t> restless_;
    /// A proxy or a filter changed since the last detection: the next one detects again (fat
    /// boxes alone are followed through fresh_).
    bool changed_ = true;

    /// Empties `ids` (fresh_, stale_, moved_ or changed_ids_), clearing their `mark` in marks_.
    void unlist(std::vector<std::uint32_t>& ids, std::uint8_t mark) noexcept {
        for (const std::uint32_t id : ids) marks_[id] &= static_cast<std::uint8_t>(~mark);
        ids.clear();
    }
};

class Broadphase::Impl : public BroadphasePool {
public:
    /// What the broad phase keeps per proxy beside Bullet's own fields.
    struct Proxy : btBroadphaseProxy {
        /// Steps since the box last moved, for a static-class proxy held dynamic (restless_).
        std::uint32_t calm_steps = 0;
        bool alive = false;
        /// Its bits keep it from pairing with any other proxy of its kind (Bullet's static and
        /// kinematic objects).
        bool static_class = false;
        /// smb holds it as a static box.
        bool held_static = false;
        /// Listed in restless_.
        bool restless = false;
        /// The proxies this one is paired with in the cache (this broad phase's additions), so that
        /// destroyProxy removes its pairs one by one instead of scanning the whole cache.
        std::vector<std::uint32_t> partners;
    };

    Impl(const WorldSettings& settings, btOverlappingPairCache* pair_cache, float skin);

    // The public interface, as Broadphase documents it.
    btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, void* userPtr,
                                   int collisionFilterGroup, int collisionFilterMask);
    void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher);
    void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax);
    void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                 const btVector3& aabbMin, const btVector3& aabbMax);
    void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback);
    void calculateOverlappingPairs(btDispatcher* dispatcher);
    void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const;
    void resetPool();
    void printStats();

    // Inline here: setAabb and the passes over the proxies and the candidates call own(), live(),
    // mark_changed() and test_candidate() for every one.

    /// The live proxy behind `proxy`; UnknownIdError for any other pointer.
    Proxy& own(const btBroadphaseProxy* proxy) const {
        if (proxy != nullptr && proxy->m_uniqueId >= 0) {
            const auto id = static_cast<std::size_t>(proxy->m_uniqueId);
            if (id < slots_.size() && slots_[id].get() == proxy && slots_[id]->alive) return *slots_[id];
        }
        detail::throw_unknown_proxy();
    }
    /// The live proxy under `id`, or null (destroyed, possibly inside a callback).
    [[nodiscard]] Proxy* live(BoxId id) const noexcept {
        if (id >= slots_.size()) return nullptr;
        Proxy* proxy = slots_[id].get();
        return proxy != nullptr && proxy->alive ? proxy : nullptr;
    }
    /// Hands smb's World the fat boxes that the proxies' boxes left since the last call.
    void flush_moves();
    /// The skin of the proxy's next fat box, its box having left its fat box.
    [[nodiscard]] float next_skin(std::uint32_t id) const;
    void sync_filters();
    /// Brings the cache to the candidates whose boxes overlap now (test_candidate on each).
    void test_candidates(btDispatcher* dispatcher);
    /// Adds the candidate's pair to the cache if its boxes began to overlap, removes it if they
    /// stopped; the passes that rewrite the list call it for every candidate they keep. It skips
    /// a candidate neither of whose boxes changed since the last calculateOverlappingPairs.
    void test_candidate(Candidate& candidate, btDispatcher* dispatcher) {
        // Every calculateOverlappingPairs leaves each candidate's standing as its boxes are: while
        // neither box changes, it stands (in a pile partly asleep, most candidates).
        if (!test_all_ && ((marks_[candidate.a] | marks_[candidate.b]) & detail::changed_mark) == 0) return;
        test_new_candidate(candidate, dispatcher);
    }
    /// As test_candidate, without the skip: for a candidate new to the list.
    void test_new_candidate(Candidate& candidate, btDispatcher* dispatcher) {
        const bool overlap = detail::overlaps_branchless(boxes_[candidate.a], boxes_[candidate.b]);
        // Most candidates stay as they were: apart and still apart, or held (or refused) and still
        // overlapping. A filter callback is asked at every step.
        if (!callback_mode_ && overlap == (candidate.held != Held::apart)) return;
        settle_candidate(candidate, overlap, dispatcher);
    }
    void mark_changed(std::uint32_t id) {
        if ((marks_[id] & detail::changed_mark) != 0) return;
        marks_[id] |= detail::changed_mark;
        changed_ids_.push_back(id);
    }
    void settle_candidate(Candidate& candidate, bool overlap, btDispatcher* dispatcher);
    /// Removes the candidate's pair from the cache if it holds it. A callback of the cache may
    /// have destroyed a proxy on the way, its pairs with it. Inline: the passes over the
    /// candidates meet it for every candidate they drop, and a call out of the unit slows them.
    void drop_if_held(const Candidate& candidate, btDispatcher* dispatcher) {
        if (candidate.held != Held::held) return;
        Proxy* a = live(candidate.a);
        Proxy* b = live(candidate.b);
        if (a != nullptr && b != nullptr) drop_pair(*a, *b, dispatcher);
    }
    /// After a detection: sorts pair_keys_ and makes the candidates exactly those pairs, in
    /// order: those whose fat boxes stopped overlapping leave (and the cache, if it held them),
    /// those that began join, those that stay keep what the cache holds; every candidate is
    /// tested.
    void reconcile_candidates(btDispatcher* dispatcher);
    /// Without a detection: the candidates of the fat boxes changed in this step (fresh_), found
    /// through index_ and among the stale boxes, replace those they had.
    void update_fresh_candidates(btDispatcher* dispatcher);
    void build_index();
    /// Adds the pair to the cache and the partner lists; false when the cache refuses it.
    bool hold_pair(Proxy& a, Proxy& b);
    void drop_pair(Proxy& a, Proxy& b, btDispatcher* dispatcher);
    /// Removes the pairs of `proxy` from the cache, and from its partners' lists.
    void remove_pairs_of(Proxy& proxy, btDispatcher* dispatcher);
    /// Holds the proxy's box static in the World, or dynamic (held_static follows).
    void hold_static(Proxy& proxy, bool held);
    void settle_restless_statics();
    void set_callback_mode(bool callback_mode);

    World<float, 3> world_;
    /// The width of a proxy id in pair_keys_: pair (a, b) is (a << key_width_) | b.
    int key_width_ = 0;
    float skin_ = Broadphase::default_skin;
    std::uint32_t step_ = 0;
    std::unique_ptr<btOverlappingPairCache> owned_cache_;
    btOverlappingPairCache* cache_ = nullptr;

    /// Slot i holds the proxy whose m_uniqueId is i, or null.
    std::vector<std::unique_ptr<Proxy>> slots_;
    std::size_t live_ = 0;
    /// Pairs this broad phase added to the cache and has not removed (the partners' lists hold
    /// each twice). When the cache holds a different number, someone else added or removed
    /// pairs there, and a destroyed proxy's pairs are found by scanning the cache instead.
    std::size_t pairs_held_ = 0;
    bool callback_mode_ = false;
    /// Every candidate is tested in this calculateOverlappingPairs, changed or not: at every one
    /// while the cache has a filter callback (it may change its mind), and at the first one
    /// after it is taken away (the callback left overlapping pairs out of the cache).
    bool test_all_ = false;
};

}  // namespace smb::bullet
