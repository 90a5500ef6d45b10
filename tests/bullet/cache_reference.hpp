// SPDX-License-Identifier: MIT
#pragma once
// What a Bullet pair cache must hold, found the obvious way: every two live proxies, one by one.

#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace smb::test {

using UidPair = std::pair<int, int>;

/// Closed overlap of two proxies' boxes, as smb::overlaps.
[[nodiscard]] inline bool proxies_overlap(const btBroadphaseProxy& a, const btBroadphaseProxy& b) {
    for (int k = 0; k < 3; ++k) {
        if (a.m_aabbMin[k] > b.m_aabbMax[k] || b.m_aabbMin[k] > a.m_aabbMax[k]) return false;
    }
    return true;
}

/// Bullet's default rule for a pair, when the cache has no filter callback.
[[nodiscard]] inline bool bits_pass(const btBroadphaseProxy& a, const btBroadphaseProxy& b) {
    return (a.m_collisionFilterGroup & b.m_collisionFilterMask) != 0 &&
           (b.m_collisionFilterGroup & a.m_collisionFilterMask) != 0;
}

[[nodiscard]] inline UidPair uid_pair(const btBroadphaseProxy& a, const btBroadphaseProxy& b) {
    return std::minmax(a.m_uniqueId, b.m_uniqueId);
}

/// Every pair of `proxies` that overlaps and that the cache's rule lets pair (its filter callback
/// if it has one, else the bits), by unique ids, sorted.
[[nodiscard]] inline std::vector<UidPair> expected_pairs(const std::vector<btBroadphaseProxy*>& proxies,
                                                         const btOverlappingPairCache& cache) {
    btOverlapFilterCallback* callback = const_cast<btOverlappingPairCache&>(cache).getOverlapFilterCallback();
    std::vector<UidPair> pairs;
    for (std::size_t i = 0; i < proxies.size(); ++i) {
        for (std::size_t j = i + 1; j < proxies.size(); ++j) {
            btBroadphaseProxy* a = proxies[i];
            btBroadphaseProxy* b = proxies[j];
            if (!proxies_overlap(*a, *b)) continue;
            const bool pass = callback != nullptr ? callback->needBroadphaseCollision(a, b) : bits_pass(*a, *b);
            if (pass) pairs.push_back(uid_pair(*a, *b));
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

/// The cache's pairs by unique ids, sorted (a pair held twice appears twice).
[[nodiscard]] inline std::vector<UidPair> cache_pairs(btOverlappingPairCache& cache) {
    std::vector<UidPair> pairs;
    const btBroadphasePairArray& array = cache.getOverlappingPairArray();
    for (int i = 0; i < array.size(); ++i) pairs.push_back(uid_pair(*array[i].m_pProxy0, *array[i].m_pProxy1));
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

}  // namespace smb::test
