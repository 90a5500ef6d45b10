// SPDX-License-Identifier: MIT
#pragma once
// Drives any Bullet broad phase the way btCollisionWorld does: one proxy per body created once,
// setAabb for every moving body each step, calculateOverlappingPairs, then a walk over the pair
// cache. Bullet keeps enlarged boxes (quantized in the sweep, fattened in the trees) and lets
// stale pairs linger, so the walk keeps only exact closed overlaps of the original boxes.

#include <cstdint>
#include <memory>
#include <vector>

#include "peers/peer.hpp"

class btBroadphaseInterface;
class btBroadphaseProxy;
class btVector3;

namespace smb::bench {

class BulletBroadphasePeer : public Peer<3> {
public:
    BulletBroadphasePeer();
    ~BulletBroadphasePeer() override;

    void build(const SceneStep<3>& step, std::vector<Pair>& pairs) final;
    void step(const SceneStep<3>& step, std::vector<Pair>& pairs) final;

protected:
    /// The broad phase for a scene whose first step has `box_count` boxes within [low, high].
    virtual std::unique_ptr<btBroadphaseInterface> create_broadphase(const btVector3& low, const btVector3& high,
                                                                     std::size_t box_count) = 0;

    /// Proxies the broad phase can hold at once (the sweep preallocates its handles).
    std::size_t proxy_limit_ = ~std::size_t{0};

private:
    void insert(BoxId id, const BenchBox<3>& box);
    void remove(BoxId id);
    void collect_exact_pairs(std::vector<Pair>& pairs);

    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::vector<btBroadphaseProxy*> proxy_of_slot_;
    std::vector<BenchBox<3>> box_of_slot_;
    std::vector<BoxId> id_of_slot_;
    std::vector<std::uint32_t> free_slots_;
    std::size_t live_proxies_ = 0;
    std::vector<std::uint32_t> slot_of_id_;  // indexed by id: the scenes' ids are dense
};

}  // namespace smb::bench
