// SPDX-License-Identifier: MIT
#include <btBulletCollisionCommon.h>

#include "peers/bullet_broadphase_peer.hpp"
#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

class BulletDbvtPeer final : public BulletBroadphasePeer {
protected:
    std::unique_ptr<btBroadphaseInterface> create_broadphase(const btVector3&, const btVector3&, std::size_t) override {
        return std::make_unique<btDbvtBroadphase>();
    }
};

}  // namespace

std::unique_ptr<Peer<3>> make_bullet_dbvt_peer() { return std::make_unique<BulletDbvtPeer>(); }

}  // namespace smb::bench
