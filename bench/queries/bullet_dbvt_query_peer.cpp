// SPDX-License-Identifier: MIT
#include <btBulletCollisionCommon.h>

#include <cstdint>

#include "queries/query_peer.hpp"

namespace smb::bench {
namespace {

btDbvtVolume volume_of(const Box<float, 3>& b) {
    return btDbvtVolume::FromMM(btVector3(b.min[0], b.min[1], b.min[2]), btVector3(b.max[0], b.max[1], b.max[2]));
}

// Bullet's dynamic AABB tree as btDbvtBroadphase uses it: leaves inserted one by one (optionally
// rebuilt top-down afterwards), box queries by collideTV (its aabbTest), rays by rayTestInternal
// with the persistent stack and the setup of btCollisionWorld::rayTest. Its ray walk keeps the
// whole segment (btDbvtBroadphase reads lambda_max once), so a nearest cast takes the least of
// all the hits.
class BulletDbvtQueryPeer final : public QueryPeer<3> {
public:
    explicit BulletDbvtQueryPeer(bool top_down) : top_down_(top_down) {}

    std::string name() const override { return top_down_ ? "Bullet btDbvt (top-down)" : "Bullet btDbvt"; }

    void build(std::span<const Box<float, 3>> boxes) override {
        tree_.clear();
        boxes_ = boxes;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            tree_.insert(volume_of(boxes[i]), reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
        }
        if (top_down_) tree_.optimizeTopDown();
    }

    void query(const Box<float, 3>& q, std::vector<BoxId>& out) override {
        out.clear();
        struct Collect : btDbvt::ICollide {
            const BulletDbvtQueryPeer* self;
            const Box<float, 3>* q;
            std::vector<BoxId>* out;
            void Process(const btDbvtNode* leaf) override {
                const auto i = static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(leaf->data));
                if (overlaps(*q, self->boxes_[i])) out->push_back(i);
            }
        } collect;
        collect.self = this;
        collect.q = &q;
        collect.out = &out;
        tree_.collideTV(tree_.m_root, volume_of(q), collect);
    }

    void cast(const Ray<float, 3>& ray, RayHits mode, std::vector<RayHit<float>>& out) override {
        out.clear();
        const btVector3 from(ray.origin[0], ray.origin[1], ray.origin[2]);
        const btVector3 to = from + btVector3(ray.direction[0], ray.direction[1], ray.direction[2]) * ray.max_t;
        btVector3 dir = to - from;
        dir.normalize();
        btVector3 inverse;
        unsigned int signs[3];
        for (int k = 0; k < 3; ++k) {
            inverse[k] = dir[k] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / dir[k];
            signs[k] = inverse[k] < 0;
        }
        const btScalar lambda_max = dir.dot(to - from);
        struct Collect : btDbvt::ICollide {
            const BulletDbvtQueryPeer* self;
            const Ray<float, 3>* ray;
            std::vector<RayHit<float>>* out;
            void Process(const btDbvtNode* leaf) override {
                const auto i = static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(leaf->data));
                if (const auto t = ray_entry(*ray, self->boxes_[i])) out->push_back({i, static_cast<float>(*t)});
            }
        } collect;
        collect.self = this;
        collect.ray = &ray;
        collect.out = &out;
        const btVector3 zero(0, 0, 0);
        tree_.rayTestInternal(tree_.m_root, from, to, inverse, signs, lambda_max, zero, zero, stack_, collect);
        finish_hits(mode, out);
    }

private:
    bool top_down_;
    btDbvt tree_;
    std::span<const Box<float, 3>> boxes_;
    btAlignedObjectArray<const btDbvtNode*> stack_;
};

}  // namespace

std::unique_ptr<QueryPeer<3>> make_bullet_dbvt_query_peer(bool top_down) {
    return std::make_unique<BulletDbvtQueryPeer>(top_down);
}

}  // namespace smb::bench
