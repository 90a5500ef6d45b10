// SPDX-License-Identifier: MIT
// rayTest and aabbTest through the world's query index, and what the broad phase reports of
// itself.

#include <algorithm>
#include <cstdio>
#include <limits>

#include "bullet/broadphase_impl.hpp"
#include "smb/query.hpp"

namespace smb::bullet {

void Broadphase::Impl::rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                               const btVector3& aabbMin, const btVector3& aabbMax) {
    flush_moves();
    // Bullet's callbacks measure lambda along the unit direction from rayFrom to rayTo
    // (m_lambda_max = |rayTo - rayFrom| to start with).
    const btVector3 offset = rayTo - rayFrom;
    const float length = offset.length();
    const btVector3 direction = length > 0 ? offset / length : btVector3(0, 0, 0);
    const Ray<float, 3> ray{{rayFrom.x(), rayFrom.y(), rayFrom.z()},
                            {direction.x(), direction.y(), direction.z()},
                            rayCallback.m_lambda_max};
    if (!is_valid(ray)) return;  // a NaN or negative m_lambda_max: nothing lies within it

    std::vector<RayHit<float>> hits;
    if (aabbMin.isZero() && aabbMax.isZero()) {
        // The World holds fat boxes: a ray enters each proxy's box no sooner than its fat box,
        // so the fat boxes' hits hold every hit, to be measured on the boxes themselves.
        world_.cast_ray(ray, RayHits::all, hits);
        std::size_t kept = 0;
        for (const RayHit<float>& hit : hits) {
            if (const auto t = ray_entry(ray, boxes_[hit.id]))
                hits[kept++] = RayHit<float>{hit.id, static_cast<float>(*t)};
        }
        hits.resize(kept);
    } else {
        // A swept shape: btDbvt grows each box by the shape's box, [min - aabbMax, max - aabbMin].
        // The boxes so grown that the segment enters are those that overlap the segment's own
        // box grown the other way.
        Box<float, 3> swept;
        for (int k = 0; k < 3; ++k) {
            const float end = ray.origin[k] + ray.direction[k] * ray.max_t;
            swept.min[k] = std::min(ray.origin[k], end) + aabbMin[k];
            swept.max[k] = std::max(ray.origin[k], end) + aabbMax[k];
        }
        if (!is_valid(swept)) return;
        std::vector<BoxId> candidates;
        world_.query(swept, candidates);
        for (const BoxId id : candidates) {
            const Proxy* proxy = live(id);
            if (proxy == nullptr) continue;
            Box<float, 3> grown;
            for (int k = 0; k < 3; ++k) {
                grown.min[k] = proxy->m_aabbMin[k] - aabbMax[k];
                grown.max[k] = proxy->m_aabbMax[k] - aabbMin[k];
            }
            if (const auto t = ray_entry(ray, grown)) hits.push_back(RayHit<float>{id, static_cast<float>(*t)});
        }
    }
    std::sort(hits.begin(), hits.end(),
              [](const RayHit<float>& a, const RayHit<float>& b) { return a.t != b.t ? a.t < b.t : a.id < b.id; });
    for (const RayHit<float>& hit : hits) {
        // The callback may have shortened the ray (a closer hit found).
        if (!(hit.t <= rayCallback.m_lambda_max)) break;
        Proxy* proxy = live(hit.id);
        if (proxy == nullptr) continue;  // destroyed by the callback
        if (!rayCallback.process(proxy)) break;
    }
}

void Broadphase::Impl::aabbTest(const btVector3& aabbMin, const btVector3& aabbMax,
                                btBroadphaseAabbCallback& callback) {
    const Box<float, 3> box = detail::checked_box(aabbMin, aabbMax, "aabbTest");
    flush_moves();
    std::vector<BoxId> ids;
    world_.query(box, ids);
    for (const BoxId id : ids) {
        Proxy* proxy = live(id);
        // The World answers for the fat boxes: those whose proxy's box misses are left out.
        if (proxy == nullptr || !overlaps(box, boxes_[id])) continue;
        if (!callback.process(proxy)) break;
    }
}

void Broadphase::Impl::getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const {
    constexpr float inf = std::numeric_limits<float>::infinity();
    btVector3 low(inf, inf, inf);
    btVector3 high(-inf, -inf, -inf);
    for (const auto& slot : slots_) {
        if (!slot || !slot->alive) continue;
        low.setMin(slot->m_aabbMin);
        high.setMax(slot->m_aabbMax);
    }
    if (live_ == 0) {
        low.setZero();
        high.setZero();
    }
    aabbMin = low;
    aabbMax = high;
}

void Broadphase::Impl::resetPool() {
    if (live_ != 0) return;
    world_.clear();
    static_cast<BroadphasePool&>(*this) = BroadphasePool{};
    slots_.clear();
    slots_.shrink_to_fit();
}

void Broadphase::Impl::printStats() {
    std::printf("smb::bullet::Broadphase: %zu proxies, %d pairs in the cache, %zu boxes held static, %zu bytes\n",
                live_, cache_->getNumOverlappingPairs(),
                static_cast<std::size_t>(std::count_if(slots_.begin(), slots_.end(),
                                                       [](const auto& slot) { return slot && slot->held_static; })),
                world_.bytes_held() + (pair_keys_.capacity() + key_spare_.capacity()) * sizeof(std::uint64_t) +
                    candidates_.capacity() * sizeof(Candidate));
}

}  // namespace smb::bullet
