// SPDX-License-Identifier: MIT
// The skin of smb::bullet::Broadphase (its World holds fat boxes, the cache the pairs of the
// proxies' own boxes) against the brute force: boxes that jitter inside their fat boxes while
// their overlaps begin and end, boxes that leave them a little or far, a few at a time (followed
// without a detection) or many; and a pair that goes on overlapping is never taken out of the
// cache, so its manifold persists.

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include "bullet/cache_reference.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

using smb::bullet::Broadphase;
using smb::test::UidPair;

/// A hashed cache that counts, by unique ids, the pairs removed since it was last asked.
class WatchedCache : public btHashedOverlappingPairCache {
public:
    void* removeOverlappingPair(btBroadphaseProxy* a, btBroadphaseProxy* b, btDispatcher* dispatcher) override {
        removed.insert(smb::test::uid_pair(*a, *b));
        return btHashedOverlappingPairCache::removeOverlappingPair(a, b, dispatcher);
    }
    std::set<UidPair> removed;
};

/// A lattice of unit boxes 1.02 apart (a gap of 0.02), each jittering by up to `jitter` a step
/// around its place, so that neighbours begin and stop touching; every step `far_movers` boxes
/// are moved by up to `far` (out of any skin below it) and put back later. A share `resting` of
/// the boxes, picked afresh each step, keep their boxes (Bullet sets a sleeping body's box again
/// unchanged).
class JitteringLattice {
public:
    JitteringLattice(Broadphase& broadphase, int side, unsigned seed) : broadphase_(broadphase), random_(seed) {
        for (int x = 0; x < side; ++x) {
            for (int y = 0; y < 3; ++y) {
                for (int z = 0; z < side; ++z) {
                    const btVector3 place(1.02f * static_cast<float>(x), 1.02f * static_cast<float>(y),
                                          1.02f * static_cast<float>(z));
                    // Every fifth proxy in a group of its own that does not pair with itself.
                    const bool apart = places_.size() % 5 == 0;
                    places_.push_back(place);
                    proxies_.push_back(broadphase_.createProxy(
                        place, place + btVector3(1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr,
                        apart ? 2 : btBroadphaseProxy::DefaultFilter,
                        apart ? btBroadphaseProxy::DefaultFilter : btBroadphaseProxy::AllFilter, nullptr));
                }
            }
        }
    }

    void step(float jitter, int far_movers, float far, float resting = 0) {
        std::uniform_real_distribution<float> shake(-jitter, jitter);
        std::bernoulli_distribution rests(resting);
        std::uniform_real_distribution<float> throw_far(-far, far);
        std::uniform_int_distribution<std::size_t> pick(0, proxies_.size() - 1);
        std::vector<btVector3> offsets(proxies_.size());
        for (btVector3& offset : offsets) offset = btVector3(shake(random_), shake(random_), shake(random_));
        for (int i = 0; i < far_movers; ++i) {
            offsets[pick(random_)] = btVector3(throw_far(random_), throw_far(random_), throw_far(random_));
        }
        for (std::size_t i = 0; i < proxies_.size(); ++i) {
            if (rests(random_)) {
                const btVector3 min = proxies_[i]->m_aabbMin;
                const btVector3 max = proxies_[i]->m_aabbMax;
                broadphase_.setAabb(proxies_[i], min, max, nullptr);
                continue;
            }
            const btVector3 min = places_[i] + offsets[i];
            broadphase_.setAabb(proxies_[i], min, min + btVector3(1, 1, 1), nullptr);
        }
    }

    /// Destroys a proxy and makes a new one in its place (the next step detects again).
    void replace_one() {
        const std::size_t at = std::uniform_int_distribution<std::size_t>(0, proxies_.size() - 1)(random_);
        const btVector3 min = proxies_[at]->m_aabbMin;
        const btVector3 max = proxies_[at]->m_aabbMax;
        broadphase_.destroyProxy(proxies_[at], nullptr);
        proxies_[at] = broadphase_.createProxy(min, max, BOX_SHAPE_PROXYTYPE, nullptr, btBroadphaseProxy::DefaultFilter,
                                               btBroadphaseProxy::AllFilter, nullptr);
    }

    [[nodiscard]] const std::vector<btBroadphaseProxy*>& proxies() const { return proxies_; }

private:
    Broadphase& broadphase_;
    std::mt19937 random_;
    std::vector<btVector3> places_;
    std::vector<btBroadphaseProxy*> proxies_;
};

/// Steps the lattice, checking after each calculateOverlappingPairs that the cache holds exactly
/// the overlapping pairs, and that no pair overlapping before and after was removed.
/// Pairs proxies whose unique ids differ by an odd number, whatever their bits.
struct OddDifference : btOverlapFilterCallback {
    bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override {
        return ((a->m_uniqueId - b->m_uniqueId) & 1) != 0;
    }
};

void run_lattice(float skin, float jitter, int far_movers, float far, int steps, bool with_callback = false,
                 float resting = 0) {
    WatchedCache cache;
    OddDifference callback;
    if (with_callback) cache.setOverlapFilterCallback(&callback);
    Broadphase broadphase({}, &cache, skin);
    JitteringLattice lattice(broadphase, 12, 3);
    broadphase.calculateOverlappingPairs(nullptr);
    std::vector<UidPair> before = smb::test::expected_pairs(lattice.proxies(), cache);
    ASSERT_EQ(smb::test::cache_pairs(cache), before);
    std::size_t began = 0;
    std::size_t ended = 0;
    for (int step = 0; step < steps; ++step) {
        // Now and then every box leaves its skin, or a proxy is replaced: a detection after steps
        // followed without one.
        lattice.step(step % 10 == 9 ? 0.3f : jitter, far_movers, far, resting);
        if (step % 13 == 12) lattice.replace_one();
        cache.removed.clear();
        broadphase.calculateOverlappingPairs(nullptr);
        const std::vector<UidPair> now = smb::test::expected_pairs(lattice.proxies(), cache);
        ASSERT_EQ(smb::test::cache_pairs(cache), now) << "skin " << skin << ", step " << step;
        std::vector<UidPair> kept;
        std::set_intersection(before.begin(), before.end(), now.begin(), now.end(), std::back_inserter(kept));
        for (const UidPair& pair : kept) {
            ASSERT_EQ(cache.removed.count(pair), 0u) << "a pair that kept overlapping was removed, step " << step;
        }
        if (step % 13 == 12) {
            // The replaced proxy's pairs went with it: compare by ids, not by persistence.
            before = now;
            continue;
        }
        began += now.size() - kept.size();
        ended += before.size() - kept.size();
        before = now;
    }
    // The jitter makes and breaks contacts: the test is not vacuous.
    EXPECT_GT(began, 100u);
    EXPECT_GT(ended, 100u);
}

TEST(BulletSkin, BoxesJitteringInsideTheirFatBoxesMakeAndBreakExactPairs) {
    // Jitter 0.02 inside a skin of 0.05: the World sees no change, the cache every flip.
    run_lattice(0.05f, 0.02f, 0, 0, 40);
}

TEST(BulletSkin, AFewBoxesLeavingTheirFatBoxesAreFollowedWithoutADetection) {
    // 8 of 432 boxes a step leave their skins, some by a little (drifting), some far.
    run_lattice(0.05f, 0.02f, 8, 0.08f, 60);
    run_lattice(0.05f, 0.02f, 8, 3.0f, 60);
    run_lattice(0.05f, 0.02f, 8, 0.08f, 40, true);  // the cache's filter callback decides
}

TEST(BulletSkin, ManyBoxesLeavingAndOtherSkins) {
    run_lattice(0.05f, 0.2f, 0, 0, 20);  // every box leaves: a detection every step
    run_lattice(0.0f, 0.02f, 8, 3.0f, 30);
    run_lattice(0.5f, 0.02f, 8, 3.0f, 30);
}

TEST(BulletSkin, OnlyTheCandidatesOfChangedBoxesAreTestedAndThePairsStayExact) {
    // Nine boxes in ten keep their boxes each step: the candidates with an end that moved are
    // tested, whichever end it is, on every path (no detection, a few fat boxes followed, many).
    run_lattice(0.05f, 0.02f, 0, 0, 40, false, 0.9f);
    run_lattice(0.05f, 0.02f, 4, 0.08f, 40, false, 0.9f);
    run_lattice(0.05f, 0.02f, 4, 3.0f, 40, false, 0.9f);
    run_lattice(0.05f, 0.02f, 4, 0.08f, 30, true, 0.9f);
    run_lattice(0.0f, 0.02f, 4, 3.0f, 30, false, 0.9f);
}

TEST(BulletSkin, PairsAFilterCallbackLeftOutComeInWhenItIsTakenAway) {
    btHashedOverlappingPairCache cache;
    struct Nothing : btOverlapFilterCallback {
        bool needBroadphaseCollision(btBroadphaseProxy*, btBroadphaseProxy*) const override { return false; }
    } nothing;
    cache.setOverlapFilterCallback(&nothing);
    Broadphase broadphase({}, &cache, 0.05f);
    for (const float x : {0.0f, 0.5f}) {
        broadphase.createProxy(btVector3(x, 0, 0), btVector3(x + 1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr,
                               btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, nullptr);
    }
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 0);
    // No box changes: the pair is there at the next step all the same.
    cache.setOverlapFilterCallback(nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 1);
}

TEST(BulletSkin, ABoxLeavingItsFatBoxStepByStep) {
    Broadphase broadphase({}, nullptr, 0.05f);
    btOverlappingPairCache& cache = *broadphase.getOverlappingPairCache();
    auto make = [&](float x) {
        return broadphase.createProxy(btVector3(x, 0, 0), btVector3(x + 1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr,
                                      btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, nullptr);
    };
    btBroadphaseProxy* still = make(0.0f);
    btBroadphaseProxy* mover = make(1.03f);
    const std::vector<btBroadphaseProxy*> both{still, mover};
    // 0.01 a step towards the still box, through touching (at 1.0), and on: inside the skin
    // first, then out of it.
    for (int step = 0; step < 12; ++step) {
        const float x = 1.03f - 0.01f * static_cast<float>(step);
        broadphase.setAabb(mover, btVector3(x, 0, 0), btVector3(x + 1, 1, 1), nullptr);
        broadphase.calculateOverlappingPairs(nullptr);
        EXPECT_EQ(smb::test::cache_pairs(cache), smb::test::expected_pairs(both, cache)) << "step " << step;
    }
    EXPECT_EQ(cache.getNumOverlappingPairs(), 1);
    // Far away and back.
    broadphase.setAabb(mover, btVector3(10, 0, 0), btVector3(11, 1, 1), nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 0);
    broadphase.setAabb(mover, btVector3(1, 0, 0), btVector3(2, 1, 1), nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_EQ(cache.getNumOverlappingPairs(), 1);
    // aabbTest answers for the boxes, not the fat boxes.
    struct Count : btBroadphaseAabbCallback {
        int seen = 0;
        bool process(const btBroadphaseProxy*) override {
            ++seen;
            return true;
        }
    } count;
    broadphase.aabbTest(btVector3(-0.04f, 0, 0), btVector3(-0.01f, 1, 1), count);
    EXPECT_EQ(count.seen, 0);
}

/// The fat box smb's World holds for the proxy, less the proxy's box: the skin on each side
/// (equal on every side up to rounding; the least is returned).
float skin_of(const Broadphase& broadphase, const btBroadphaseProxy* proxy) {
    const smb::Box<float, 3> fat = broadphase.world().box(static_cast<smb::BoxId>(proxy->m_uniqueId));
    float least = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 3; ++k) {
        least = std::min({least, proxy->m_aabbMin[k] - fat.min[k], fat.max[k] - proxy->m_aabbMax[k]});
    }
    return least;
}

TEST(BulletSkin, ABoxCreepingGetsAThickerSkinAndAFastOneNone) {
    // A column of unit boxes creeping 0.004 a step along x, into touch with a still column beside
    // it and out again: each leaves its first fat box (skin 0.05) after a dozen steps and, having
    // kept still that long, gets a skin of 0.1; thrown far, it gets none; the pairs stay exact.
    WatchedCache cache;
    Broadphase broadphase({}, &cache, 0.05f);
    // Six unit boxes 0.01 apart up the y axis, from x.
    const auto column = [&broadphase](float x) {
        std::vector<btBroadphaseProxy*> boxes;
        for (int i = 0; i < 6; ++i) {
            const btVector3 min(x, 1.01f * static_cast<float>(i), 0);
            boxes.push_back(broadphase.createProxy(min, min + btVector3(1, 1, 1), BOX_SHAPE_PROXYTYPE, nullptr,
                                                   btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter,
                                                   nullptr));
        }
        return boxes;
    };
    std::vector<btBroadphaseProxy*> proxies = column(0.0f);
    const std::vector<btBroadphaseProxy*> creepers = column(1.1f);
    proxies.insert(proxies.end(), creepers.begin(), creepers.end());
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_NEAR(skin_of(broadphase, creepers[0]), 0.05f, 1e-5f);
    bool thicker = false;
    int most_pairs = 0;
    for (int step = 1; step <= 120; ++step) {
        // In by 0.48 over 60 steps, then out again.
        const float x = 1.1f - 0.004f * static_cast<float>(step <= 60 ? step : 120 - step);
        for (std::size_t i = 0; i < creepers.size(); ++i) {
            const btVector3 min(x, 1.01f * static_cast<float>(i), 0);
            broadphase.setAabb(creepers[i], min, min + btVector3(1, 1, 1), nullptr);
        }
        broadphase.calculateOverlappingPairs(nullptr);
        ASSERT_EQ(smb::test::cache_pairs(cache), smb::test::expected_pairs(proxies, cache)) << "step " << step;
        const float skin = skin_of(broadphase, creepers[0]);
        EXPECT_TRUE(skin >= 0.0f && skin <= 0.1001f) << "step " << step << ": skin " << skin;
        thicker = thicker || skin > 0.075f;
        most_pairs = std::max(most_pairs, cache.getNumOverlappingPairs());
    }
    EXPECT_TRUE(thicker);
    EXPECT_EQ(most_pairs, 6);                      // each in touch with the still box beside it
    EXPECT_EQ(cache.getNumOverlappingPairs(), 0);  // apart again (the columns' boxes are 0.01 apart)
    // Thrown far: no skin.
    broadphase.setAabb(creepers[0], btVector3(20, 0, 0), btVector3(21, 1, 1), nullptr);
    broadphase.calculateOverlappingPairs(nullptr);
    EXPECT_NEAR(skin_of(broadphase, creepers[0]), 0.0f, 1e-5f);
    EXPECT_EQ(smb::test::cache_pairs(cache), smb::test::expected_pairs(proxies, cache));
}

TEST(BulletSkin, ASkinThatIsNotFiniteAndPositiveIsRefused) {
    EXPECT_THROW(Broadphase({}, nullptr, -0.1f), smb::ArgumentError);
    EXPECT_THROW(Broadphase({}, nullptr, std::numeric_limits<float>::infinity()), smb::ArgumentError);
    EXPECT_NO_THROW(Broadphase({}, nullptr, 0.0f));
}

}  // namespace
