// SPDX-License-Identifier: MIT
#include "peers/bullet_broadphase_peer.hpp"

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <stdexcept>

namespace smb::bench {
namespace {

btVector3 to_bullet(const std::array<float, 3>& point) { return {point[0], point[1], point[2]}; }

constexpr std::uint32_t no_slot = ~std::uint32_t{0};

// Bullet calls the owner of a proxy its "client object": we store the slot index there.
void* slot_as_client(std::uint32_t slot) { return reinterpret_cast<void*>(static_cast<std::uintptr_t>(slot)); }
std::uint32_t slot_of_client(const btBroadphaseProxy* proxy) {
    return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(proxy->m_clientObject));
}

}  // namespace

BulletBroadphasePeer::BulletBroadphasePeer() = default;
BulletBroadphasePeer::~BulletBroadphasePeer() {
    if (!broadphase_) return;
    for (btBroadphaseProxy* proxy : proxy_of_slot_)
        if (proxy != nullptr) broadphase_->destroyProxy(proxy, nullptr);
}

void BulletBroadphasePeer::build(const SceneStep<3>& step, std::vector<Pair>& pairs) {
    std::array<float, 3> low{0, 0, 0}, high{1, 1, 1};
    if (step.size() > 0) {
        low = step.boxes[0].min;
        high = step.boxes[0].max;
    }
    for (const auto& box : step.boxes) {
        for (int k = 0; k < 3; ++k) {
            low[k] = std::min(low[k], box.min[k]);
            high[k] = std::max(high[k], box.max[k]);
        }
    }
    // The scenes keep boxes inside their cube; the margin only spares the sweep's quantizer
    // from clamping (which would stay correct, just coarser).
    for (int k = 0; k < 3; ++k) {
        const float margin = 0.05f * (high[k] - low[k]) + 1.0f;
        low[k] -= margin;
        high[k] += margin;
    }
    broadphase_ = create_broadphase(to_bullet(low), to_bullet(high), step.size());
    for (std::size_t i = 0; i < step.size(); ++i) insert(step.ids[i], step.boxes[i]);
    broadphase_->calculateOverlappingPairs(nullptr);
    collect_exact_pairs(pairs);
}

void BulletBroadphasePeer::step(const SceneStep<3>& step, std::vector<Pair>& pairs) {
    for (BoxId id : step.removed_ids) remove(id);
    for (std::size_t i = 0; i < step.first_inserted; ++i) {
        const std::uint32_t slot = slot_of_id_[step.ids[i]];
        box_of_slot_[slot] = step.boxes[i];
        broadphase_->setAabb(proxy_of_slot_[slot], to_bullet(step.boxes[i].min), to_bullet(step.boxes[i].max), nullptr);
    }
    for (std::size_t i = step.first_inserted; i < step.size(); ++i) insert(step.ids[i], step.boxes[i]);
    broadphase_->calculateOverlappingPairs(nullptr);
    collect_exact_pairs(pairs);
}

void BulletBroadphasePeer::insert(BoxId id, const BenchBox<3>& box) {
    if (live_proxies_ == proxy_limit_) throw std::runtime_error("the Bullet broad phase is full");
    ++live_proxies_;
    std::uint32_t slot;
    if (!free_slots_.empty()) {
        slot = free_slots_.back();
        free_slots_.pop_back();
    } else {
        slot = static_cast<std::uint32_t>(proxy_of_slot_.size());
        proxy_of_slot_.push_back(nullptr);
        box_of_slot_.emplace_back();
        id_of_slot_.push_back(0);
    }
    btBroadphaseProxy* proxy =
        broadphase_->createProxy(to_bullet(box.min), to_bullet(box.max), BOX_SHAPE_PROXYTYPE, slot_as_client(slot),
                                 btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, nullptr);
    proxy_of_slot_[slot] = proxy;
    box_of_slot_[slot] = box;
    id_of_slot_[slot] = id;
    if (id >= slot_of_id_.size()) slot_of_id_.resize(std::max<std::size_t>(id + 1, 2 * slot_of_id_.size()), no_slot);
    slot_of_id_[id] = slot;
}

void BulletBroadphasePeer::remove(BoxId id) {
    const std::uint32_t slot = slot_of_id_[id];
    broadphase_->destroyProxy(proxy_of_slot_[slot], nullptr);
    proxy_of_slot_[slot] = nullptr;
    --live_proxies_;
    slot_of_id_[id] = no_slot;
    free_slots_.push_back(slot);
}

void BulletBroadphasePeer::collect_exact_pairs(std::vector<Pair>& pairs) {
    pairs.clear();
    const btBroadphasePairArray& cached = broadphase_->getOverlappingPairCache()->getOverlappingPairArray();
    for (int i = 0; i < cached.size(); ++i) {
        const std::uint32_t first = slot_of_client(cached[i].m_pProxy0);
        const std::uint32_t second = slot_of_client(cached[i].m_pProxy1);
        if (overlaps(box_of_slot_[first], box_of_slot_[second]))
            pairs.push_back(ordered_pair(id_of_slot_[first], id_of_slot_[second]));
    }
}

}  // namespace smb::bench
