// SPDX-License-Identifier: MIT
#include <btBulletCollisionCommon.h>

#include "peers/bullet_broadphase_peer.hpp"
#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

class BulletAxisSweepPeer final : public BulletBroadphasePeer {
protected:
    std::unique_ptr<btBroadphaseInterface> create_broadphase(const btVector3& low, const btVector3& high,
                                                             std::size_t box_count) override {
        // The sweep preallocates its handles; room for the scene to grow by half. The ray-cast
        // accelerator (a second, tree broad phase) is off: nothing here casts rays.
        const auto capacity = static_cast<unsigned>(box_count + box_count / 2 + 1024);
        proxy_limit_ = capacity - 2;  // the sweep reserves handle 0 as a sentinel
        return std::make_unique<bt32BitAxisSweep3>(low, high, capacity, nullptr, true);
    }
};

}  // namespace

std::unique_ptr<Peer<3>> make_bullet_axis_sweep_peer() { return std::make_unique<BulletAxisSweepPeer>(); }

}  // namespace smb::bench
