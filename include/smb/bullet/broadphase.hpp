// SPDX-License-Identifier: MIT
#pragma once
// smb as Bullet's broad phase: a btBroadphaseInterface that a btCollisionWorld or a
// btDiscreteDynamicsWorld takes in place of btDbvtBroadphase or btAxisSweep3 (docs/bullet.md).

#include <btBulletCollisionCommon.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "smb/box.hpp"
#include "smb/box_index.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"
#include "smb/world.hpp"

namespace smb::bullet {

/// A Bullet broad phase backed by an smb::World of float boxes (Bullet's btScalar).
///
/// The switch: `smb::bullet::Broadphase broadphase;` where a program had `btDbvtBroadphase
/// broadphase;`, and the same pointer handed to the world.
///
/// Pairs: after calculateOverlappingPairs the pair cache holds exactly the pairs of proxies whose
/// current AABBs overlap (closed: touching faces overlap) and that Bullet's filtering lets pair,
/// each once. A pair enters the cache (addOverlappingPair) at the step its boxes begin to
/// overlap and leaves it (removeOverlappingPair, with the dispatcher, so that its contact
/// manifold is freed) at the step they stop; in between it stays, with its manifold. Bullet's own
/// broad phases keep pairs of fattened boxes and drop them lazily; this one keeps none.
///
/// The skin: smb's World holds each proxy's box grown by `skin` on every side (its fat box) and
/// changes it only when the proxy's box leaves it, so that boxes that jitter in place (a pile
/// that does not fall asleep) change nothing there; the pairs of fat boxes are tested on the
/// proxies' own boxes before they reach the cache. A box that left its fat box by more than the
/// skin moves fast and is held without one until it slows down; one that had kept inside its
/// fat box for 16 steps before drifting out creeps, and is held with twice the skin. Skin 0: the
/// World holds the proxies' boxes themselves.
///
/// Filtering, as Bullet's pair cache decides it: while the cache has no overlap filter callback,
/// proxies a and b pair when (a.group & b.mask) && (b.group & a.mask), read from the proxies at
/// every calculateOverlappingPairs (changing them in between is seen); smb applies these bits in
/// its detection. A proxy whose group holds only StaticFilter and KinematicFilter bits and whose
/// mask holds neither (what btCollisionWorld gives static and kinematic objects) can never pair
/// with another such proxy; smb holds it as a static box while it does not move. While the cache
/// has a filter callback, the bits are not used (Bullet ignores them then too) and the callback
/// decides every overlapping pair, at every step.
///
/// Queries: rayTest reports the proxies whose boxes, grown by the query's (aabbMin, aabbMax) as
/// btDbvt grows them, the ray from rayFrom towards rayTo enters within a distance
/// callback.m_lambda_max (Bullet's callbacks set it to |rayTo - rayFrom|), nearest first; it
/// stops when the callback's process() returns false or the next entry lies past m_lambda_max
/// (read again after each call, so a callback that shrinks it cuts the test short). aabbTest
/// reports the proxies whose boxes overlap the query box, and stops likewise when process()
/// returns false. Proxies created inside a callback are not reported by the test under way;
/// proxies destroyed inside it are not reported afterwards.
///
/// Errors: an AABB with NaN, infinity or min > max gives smb::InvalidBoxError, a proxy that this
/// broad phase did not create, or destroyed, smb::UnknownIdError; either changes nothing. A
/// destroyed proxy's memory is kept for the next proxy created after the following
/// calculateOverlappingPairs, so a stale pointer is recognised until then (and names that new
/// proxy afterwards, as with btAxisSweep3's pool).
///
/// Not thread-safe, as Bullet's broad phases.
class Broadphase : public btBroadphaseInterface {
public:
    /// The skin unless one is given: Bullet's own margin for btDbvtBroadphase's boxes (gDbvtMargin,
    /// in the world's length unit, metres for Bullet's default tolerances).
    static constexpr float default_skin = 0.05f;

    /// `pair_cache`: the cache to maintain, as btDbvtBroadphase takes it (not owned; it must
    /// outlive the broad phase). Null: a btHashedOverlappingPairCache of its own. `skin`: how far
    /// a box may move before smb's World sees it (twice as far for a creeping box, above);
    /// ArgumentError unless finite and >= 0.
    explicit Broadphase(const WorldSettings& settings = {}, btOverlappingPairCache* pair_cache = nullptr,
                        float skin = default_skin);
    ~Broadphase() override;
    Broadphase(const Broadphase&) = delete;
    Broadphase& operator=(const Broadphase&) = delete;

    btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType, void* userPtr,
                                   int collisionFilterGroup, int collisionFilterMask,
                                   btDispatcher* dispatcher) override;
    void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
    void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
                 btDispatcher* dispatcher) override;
    void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const override;
    void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                 const btVector3& aabbMin = btVector3(0, 0, 0), const btVector3& aabbMax = btVector3(0, 0, 0)) override;
    void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) override;
    void calculateOverlappingPairs(btDispatcher* dispatcher) override;
    btOverlappingPairCache* getOverlappingPairCache() override { return cache_; }
    const btOverlappingPairCache* getOverlappingPairCache() const override { return cache_; }
    /// The union of every proxy's box; (0, 0, 0) twice when there is none.
    void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const override;
    /// With no proxy left, releases the memory the detection holds.
    void resetPool(btDispatcher* dispatcher) override;
    void printStats() override;

    /// Proxies alive.
    [[nodiscard]] std::size_t size() const noexcept { return live_; }
    /// The smb world behind the broad phase (read only: its boxes are the proxies' fat boxes
    /// under the proxies' m_uniqueId, each holding the proxy's box).
    [[nodiscard]] const World<float, 3>& world() const noexcept { return world_; }

private:
    struct Proxy;
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

    /// The live proxy behind `proxy`; UnknownIdError for any other pointer.
    Proxy& own(const btBroadphaseProxy* proxy) const;
    /// The live proxy under `id`, or null (destroyed, possibly inside a callback).
    [[nodiscard]] Proxy* live(BoxId id) const noexcept;
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
    void test_candidate(Candidate& candidate, btDispatcher* dispatcher);
    /// As test_candidate, without the skip: for a candidate new to the list.
    void test_new_candidate(Candidate& candidate, btDispatcher* dispatcher);
    /// Marks the proxy's box changed since the last calculateOverlappingPairs.
    void mark_changed(std::uint32_t id);
    void settle_candidate(Candidate& candidate, bool overlap, btDispatcher* dispatcher);
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
    void settle_restless_statics();
    void set_callback_mode(bool callback_mode);

    World<float, 3> world_;
    /// The pairs of fat boxes of the last detection as keys (src/bullet/pair_keys.hpp), sorted
    /// before the merge, and the room their radix sort works in.
    std::vector<std::uint64_t> pair_keys_;
    std::vector<std::uint64_t> key_spare_;
    std::vector<std::uint32_t> key_counts_;
    /// The width of a proxy id in pair_keys_: pair (a, b) is (a << key_width_) | b.
    int key_width_ = 0;
    float skin_ = default_skin;
    /// By id: each proxy's box (empty, pairing with nothing, once destroyed) and its fat box.
    std::vector<Box<float, 3>> boxes_;
    std::vector<Box<float, 3>> fat_boxes_;
    /// By id: the step at which the fat box was set (steps count calculateOverlappingPairs).
    std::vector<std::uint32_t> fat_since_;
    /// By id: the filter smb holds for the proxy's box (the default while the cache has a filter
    /// callback).
    std::vector<Filter> filters_;
    std::uint32_t step_ = 0;
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
    /// built; marks_ holds, by id, whether an id is listed in either, or in moved_ (fresh_mark,
    /// stale_mark, moved_mark).
    std::vector<std::uint32_t> fresh_;
    std::vector<std::uint32_t> stale_;
    std::vector<Box<float, 3>> stale_boxes_;
    std::vector<std::uint8_t> marks_;
    /// Ids whose box changed (or that were created or destroyed) since the last
    /// calculateOverlappingPairs: only the candidates they are part of are tested.
    std::vector<std::uint32_t> changed_ids_;
    std::unique_ptr<btOverlappingPairCache> owned_cache_;
    btOverlappingPairCache* cache_ = nullptr;

    /// Slot i holds the proxy whose m_uniqueId is i, or null.
    std::vector<std::unique_ptr<Proxy>> slots_;
    std::vector<std::uint32_t> free_ids_;
    /// Ids destroyed since the last detection: not given out again before it, so that a pair of
    /// ids names the same two proxies in the candidates and in the detection's pairs.
    std::vector<std::uint32_t> retired_ids_;
    std::vector<std::uint32_t> moved_;
    std::vector<BoxId> move_ids_;
    std::vector<Box<float, 3>> move_boxes_;
    /// Static-class proxies held dynamic because they moved lately.
    std::vector<std::uint32_t> restless_;
    std::size_t live_ = 0;
    /// Pairs this broad phase added to the cache and has not removed (the partners' lists hold
    /// each twice). When the cache holds a different number, someone else added or removed
    /// pairs there, and a destroyed proxy's pairs are found by scanning the cache instead.
    std::size_t pairs_held_ = 0;
    /// A proxy or a filter changed since the last detection: the next one detects again (fat
    /// boxes alone are followed through fresh_).
    bool changed_ = true;
    bool callback_mode_ = false;
    /// Every candidate is tested in this calculateOverlappingPairs, changed or not: at every one
    /// while the cache has a filter callback (it may change its mind), and at the first one
    /// after it is taken away (the callback left overlapping pairs out of the cache).
    bool test_all_ = false;
};

}  // namespace smb::bullet
