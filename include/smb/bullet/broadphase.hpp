// SPDX-License-Identifier: MIT
#pragma once
// smb as Bullet's broad phase: a btBroadphaseInterface that a btCollisionWorld or a
// btDiscreteDynamicsWorld takes in place of btDbvtBroadphase or btAxisSweep3 (docs/bullet.md).

#include <btBulletCollisionCommon.h>

#include <cstddef>
#include <memory>

#include "smb/box.hpp"
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
    btOverlappingPairCache* getOverlappingPairCache() override;
    const btOverlappingPairCache* getOverlappingPairCache() const override;
    /// The union of every proxy's box; (0, 0, 0) twice when there is none.
    void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const override;
    /// With no proxy left, releases the memory the detection holds.
    void resetPool(btDispatcher* dispatcher) override;
    void printStats() override;

    /// Proxies alive.
    [[nodiscard]] std::size_t size() const noexcept;
    /// The smb world behind the broad phase (read only: its boxes are the proxies' fat boxes
    /// under the proxies' m_uniqueId, each holding the proxy's box).
    [[nodiscard]] const World<float, 3>& world() const noexcept;

private:
    /// The proxies, the candidates and the World behind them (src/bullet/broadphase_impl.hpp).
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace smb::bullet
