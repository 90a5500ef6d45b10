// SPDX-License-Identifier: MIT
// smb::bullet::Broadphase against the brute force: the pair cache after every
// calculateOverlappingPairs of a random history of proxies created, moved, teleported, refiltered
// and destroyed; the filter callback; bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bullet/cache_reference.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

using smb::bullet::Broadphase;

#if defined(SMB_TEST_REDUCED)
constexpr int steps = 120;
constexpr int initial_proxies = 150;
#else
constexpr int steps = 400;
constexpr int initial_proxies = 400;
#endif

constexpr int static_group = btBroadphaseProxy::StaticFilter;
constexpr int static_mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter;

/// A random history of proxies in a 12-unit cube, so that boxes of up to 1.5 units meet often.
class RandomHistory {
public:
    explicit RandomHistory(Broadphase& broadphase, unsigned seed) : broadphase_(broadphase), random_(seed) {}

    btBroadphaseProxy* create() {
        btVector3 min;
        btVector3 max;
        random_box(min, max);
        int group = btBroadphaseProxy::DefaultFilter;
        int mask = btBroadphaseProxy::AllFilter;
        random_filter(group, mask);
        btBroadphaseProxy* proxy =
            broadphase_.createProxy(min, max, BOX_SHAPE_PROXYTYPE, nullptr, group, mask, nullptr);
        proxies_.push_back(proxy);
        return proxy;
    }

    void destroy_one() {
        if (proxies_.empty()) return;
        const std::size_t at = pick(proxies_.size());
        broadphase_.destroyProxy(proxies_[at], nullptr);
        proxies_[at] = proxies_.back();
        proxies_.pop_back();
    }

    /// Moves about 1 proxy in 5 a little, 1 in 100 anywhere, and gives 1 in 200 new filter bits
    /// (written into the proxy, as Bullet's users do).
    void step() {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::uniform_real_distribution<float> nudge(-0.15f, 0.15f);
        for (btBroadphaseProxy* proxy : proxies_) {
            const float roll = unit(random_);
            if (roll < 0.2f) {
                const btVector3 shift(nudge(random_), nudge(random_), nudge(random_));
                broadphase_.setAabb(proxy, proxy->m_aabbMin + shift, proxy->m_aabbMax + shift, nullptr);
            } else if (roll < 0.21f) {
                btVector3 min;
                btVector3 max;
                random_box(min, max);
                broadphase_.setAabb(proxy, min, max, nullptr);
            } else if (roll < 0.215f) {
                random_filter(proxy->m_collisionFilterGroup, proxy->m_collisionFilterMask);
            }
        }
        const int births = static_cast<int>(pick(4));
        const int deaths = static_cast<int>(pick(4));
        for (int i = 0; i < births; ++i) create();
        for (int i = 0; i < deaths; ++i) destroy_one();
    }

    [[nodiscard]] const std::vector<btBroadphaseProxy*>& proxies() const { return proxies_; }
    std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(random_); }

private:
    void random_box(btVector3& min, btVector3& max) {
        std::uniform_real_distribution<float> where(0.0f, 12.0f);
        std::uniform_real_distribution<float> size(0.0f, 1.5f);
        min = btVector3(where(random_), where(random_), where(random_));
        max = min + btVector3(size(random_), size(random_), size(random_));
        // A share of boxes that share faces exactly: touching boxes must pair.
        if (pick(8) == 0) max = min + btVector3(1, 1, 1);
        if (pick(8) == 0) min = btVector3(std::floor(min.x()), std::floor(min.y()), std::floor(min.z()));
    }

    /// Half dynamic with Bullet's defaults, a sixth static (as btCollisionWorld files static and
    /// kinematic objects), the rest random bits.
    void random_filter(int& group, int& mask) {
        const std::size_t kind = pick(6);
        if (kind < 3) {
            group = btBroadphaseProxy::DefaultFilter;
            mask = btBroadphaseProxy::AllFilter;
        } else if (kind == 3) {
            group = static_group;
            mask = static_mask;
        } else {
            group = 1 << pick(5);
            mask = static_cast<int>(pick(32));
        }
    }

    Broadphase& broadphase_;
    std::mt19937 random_;
    std::vector<btBroadphaseProxy*> proxies_;
};

void expect_cache_exact(Broadphase& broadphase, const RandomHistory& history, int step) {
    const auto expected = smb::test::expected_pairs(history.proxies(), *broadphase.getOverlappingPairCache());
    const auto held = smb::test::cache_pairs(*broadphase.getOverlappingPairCache());
    ASSERT_EQ(held, expected) << "at step " << step;
}

TEST(BulletBroadphase, CacheHoldsExactlyTheOverlappingPairsOfARandomHistory) {
    for (const unsigned seed : {1u, 2u, 3u}) {
        Broadphase broadphase;
        RandomHistory history(broadphase, seed);
        for (int i = 0; i < initial_proxies; ++i) history.create();
        for (int step = 0; step < steps; ++step) {
            history.step();
            broadphase.calculateOverlappingPairs(nullptr);
            expect_cache_exact(broadphase, history, step);
            if (HasFatalFailure()) return;
            ASSERT_EQ(broadphase.size(), history.proxies().size());
        }
    }
}

TEST(BulletBroadphase, StaticsStayExactWhenTheyMoveAndWhenTheyRest) {
    Broadphase broadphase;
    RandomHistory history(broadphase, 7);
    for (int i = 0; i < initial_proxies; ++i) history.create();
    // A kinematic body (static bits) pushed through the others for a while, then resting.
    btBroadphaseProxy* pusher = broadphase.createProxy(btVector3(0, 5, 5), btVector3(2, 7, 7), BOX_SHAPE_PROXYTYPE,
                                                       nullptr, static_group, static_mask, nullptr);
    std::vector<btBroadphaseProxy*> all = history.proxies();
    all.push_back(pusher);
    for (int step = 0; step < 60; ++step) {
        if (step < 30) {
            const btVector3 shift(0.35f, 0, 0);
            broadphase.setAabb(pusher, pusher->m_aabbMin + shift, pusher->m_aabbMax + shift, nullptr);
        } else {
            broadphase.setAabb(pusher, pusher->m_aabbMin, pusher->m_aabbMax, nullptr);  // as btCollisionWorld does
        }
        broadphase.calculateOverlappingPairs(nullptr);
        ASSERT_EQ(smb::test::cache_pairs(*broadphase.getOverlappingPairCache()),
                  smb::test::expected_pairs(all, *broadphase.getOverlappingPairCache()))
            << "at step " << step;
        // Held dynamic while it moves, static again once it has rested a while.
        const bool held_static = broadphase.world().is_static(static_cast<smb::BoxId>(pusher->m_uniqueId));
        if (step < 30) {
            EXPECT_FALSE(held_static) << "at step " << step;
        } else if (step >= 50) {
            EXPECT_TRUE(held_static) << "at step " << step;
        }
    }
    // The statics that never moved were held static from the start, a kinematic one filed in the
    // kinematic group too; a dynamic proxy never is.
    btBroadphaseProxy* kinematic = broadphase.createProxy(
        btVector3(0, 0, 0), btVector3(1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, btBroadphaseProxy::KinematicFilter,
        btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter ^ btBroadphaseProxy::KinematicFilter, nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_TRUE(broadphase.world().is_static(static_cast<smb::BoxId>(kinematic->m_uniqueId)));
    for (const btBroadphaseProxy* proxy : history.proxies()) {
        // The documented rule: Bullet's static filing, or static and kinematic bits alone in the
        // group and neither in the mask.
        const int group = proxy->m_collisionFilterGroup;
        const int mask = proxy->m_collisionFilterMask;
        constexpr int both = btBroadphaseProxy::StaticFilter | btBroadphaseProxy::KinematicFilter;
        const bool fixed =
            (group == btBroadphaseProxy::StaticFilter && (mask & btBroadphaseProxy::StaticFilter) == 0) ||
            (group != 0 && (group & ~both) == 0 && (mask & both) == 0);
        EXPECT_EQ(broadphase.world().is_static(static_cast<smb::BoxId>(proxy->m_uniqueId)), fixed);
    }
}

/// Pairs proxies whose unique ids differ by an odd number, whatever their bits.
struct OddDifference : btOverlapFilterCallback {
    bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
        return ((a->m_uniqueId - b->m_uniqueId) & 1) != 0;
    }
};

TEST(BulletBroadphase, TheCachesFilterCallbackReplacesTheBitsWhileItIsSet) {
    Broadphase broadphase;
    RandomHistory history(broadphase, 11);
    for (int i = 0; i < initial_proxies; ++i) history.create();
    OddDifference callback;
    for (int step = 0; step < 90; ++step) {
        // Set for the middle third: pairs the bits refused begin, those it refuses end.
        broadphase.getOverlappingPairCache()->setOverlapFilterCallback(step >= 30 && step < 60 ? &callback : nullptr);
        history.step();
        broadphase.calculateOverlappingPairs(nullptr);
        expect_cache_exact(broadphase, history, step);
        if (HasFatalFailure()) return;
    }
}

TEST(BulletBroadphase, AStepWithoutChangeKeepsEveryPair) {
    Broadphase broadphase;
    RandomHistory history(broadphase, 5);
    for (int i = 0; i < initial_proxies; ++i) history.create();
    broadphase.calculateOverlappingPairs(nullptr);
    const auto before = smb::test::cache_pairs(*broadphase.getOverlappingPairCache());
    EXPECT_FALSE(before.empty());
    for (btBroadphaseProxy* proxy : history.proxies()) {
        broadphase.setAabb(proxy, proxy->m_aabbMin, proxy->m_aabbMax, nullptr);
    }
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(smb::test::cache_pairs(*broadphase.getOverlappingPairCache()), before);
}

TEST(BulletBroadphase, ADestroyedProxyLeavesNoPairInTheCacheEvenOnesAddedByOthers) {
    // destroyProxy removes the proxy's own pairs by name while the cache holds only what the
    // broad phase put there, and scans the cache once someone else has added a pair too.
    Broadphase broadphase;
    btOverlappingPairCache& cache = *broadphase.getOverlappingPairCache();
    auto make = [&](float x) {
        return broadphase.createProxy(btVector3(x, 0, 0), btVector3(x + 1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr,
                                      btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, nullptr);
    };
    btBroadphaseProxy* a = make(0.0f);
    btBroadphaseProxy* b = make(0.5f);
    btBroadphaseProxy* c = make(1.0f);
    btBroadphaseProxy* far = make(10.0f);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 3);  // a-b, a-c (touching), b-c
    broadphase.destroyProxy(a, nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 1);
    EXPECT_NE(cache.findPair(b, c), nullptr);
    cache.addOverlappingPair(b, far);  // not an overlap: a pair of someone else's
    broadphase.destroyProxy(far, nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 1);
    EXPECT_EQ(cache.findPair(b, far), nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(smb::test::cache_pairs(cache), smb::test::expected_pairs({b, c}, cache));
}

TEST(BulletBroadphase, BadInputThrowsAndChangesNothing) {
    Broadphase broadphase;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const btVector3 zero(0, 0, 0);
    const btVector3 one(1, 1, 1);
    EXPECT_THROW((void)broadphase.createProxy(zero, btVector3(nan, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr),
                 smb::InvalidBoxError);
    EXPECT_THROW((void)broadphase.createProxy(one, zero, BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr),
                 smb::InvalidBoxError);
    EXPECT_EQ(broadphase.size(), 0u);

    btBroadphaseProxy* a = broadphase.createProxy(zero, one, BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    btBroadphaseProxy* b = broadphase.createProxy(one, one * 2, BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    EXPECT_THROW(broadphase.setAabb(a, zero, btVector3(1, std::numeric_limits<float>::infinity(), 1), nullptr),
                 smb::InvalidBoxError);
    EXPECT_THROW(broadphase.setAabb(a, one, zero, nullptr), smb::InvalidBoxError);
    btVector3 min;
    btVector3 max;
    broadphase.getAabb(a, min, max);
    EXPECT_EQ(min, zero);
    EXPECT_EQ(max, one);

    btBroadphaseProxy stranger(zero, one, nullptr, 1, -1);
    stranger.m_uniqueId = a->m_uniqueId;
    EXPECT_THROW(broadphase.setAabb(&stranger, zero, one, nullptr), smb::UnknownIdError);
    EXPECT_THROW(broadphase.destroyProxy(nullptr, nullptr), smb::UnknownIdError);

    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);  // a and b touch at a corner
    broadphase.destroyProxy(b, nullptr);
    EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
    EXPECT_THROW(broadphase.destroyProxy(b, nullptr), smb::UnknownIdError);
    EXPECT_THROW(broadphase.getAabb(b, min, max), smb::UnknownIdError);
    EXPECT_EQ(broadphase.size(), 1u);
}

TEST(BulletBroadphase, BoundsAndResetPool) {
    Broadphase broadphase;
    btVector3 min;
    btVector3 max;
    broadphase.getBroadphaseAabb(min, max);
    EXPECT_EQ(min, btVector3(0, 0, 0));
    EXPECT_EQ(max, btVector3(0, 0, 0));
    btBroadphaseProxy* a =
        broadphase.createProxy(btVector3(-3, 0, 0), btVector3(0, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    btBroadphaseProxy* b =
        broadphase.createProxy(btVector3(0, -2, 0), btVector3(1, 1, 5), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    broadphase.getBroadphaseAabb(min, max);
    EXPECT_EQ(min, btVector3(-3, -2, 0));
    EXPECT_EQ(max, btVector3(1, 1, 5));
    broadphase.calculateOverlappingPairs(nullptr);
    broadphase.resetPool(nullptr);  // proxies alive: nothing happens
    EXPECT_EQ(broadphase.size(), 2u);
    broadphase.destroyProxy(a, nullptr);
    broadphase.destroyProxy(b, nullptr);
    broadphase.resetPool(nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
    btBroadphaseProxy* c =
        broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    btBroadphaseProxy* d =
        broadphase.createProxy(btVector3(1, 1, 1), btVector3(2, 2, 2), BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
    EXPECT_NE(c, d);
}

}  // namespace
