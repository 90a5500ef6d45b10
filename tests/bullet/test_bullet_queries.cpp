// SPDX-License-Identifier: MIT
// smb::bullet::Broadphase's rayTest and aabbTest against the brute force, their early outs, and
// proxies created and destroyed from inside their callbacks.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "bullet/cache_reference.hpp"
#include "smb/bullet/broadphase.hpp"
#include "smb/query.hpp"

namespace {

using smb::bullet::Broadphase;

#if defined(SMB_TEST_REDUCED)
constexpr int queries = 60;
#else
constexpr int queries = 300;
#endif

/// Bullet's ray callbacks measure lambda in distance along the unit direction.
struct RayRecorder : btBroadphaseRayCallback {
    explicit RayRecorder(float lambda_max) { m_lambda_max = lambda_max; }
    bool process(const btBroadphaseProxy* proxy) override {
        visited.push_back(proxy->m_uniqueId);
        return on_visit ? on_visit(*proxy, *this) : true;
    }
    std::vector<int> visited;
    std::function<bool(const btBroadphaseProxy&, RayRecorder&)> on_visit;
};

struct BoxRecorder : btBroadphaseAabbCallback {
    bool process(const btBroadphaseProxy* proxy) override {
        visited.push_back(proxy->m_uniqueId);
        return on_visit ? on_visit(*proxy) : true;
    }
    std::vector<int> visited;
    std::function<bool(const btBroadphaseProxy&)> on_visit;
};

class BulletQueries : public ::testing::Test {
protected:
    void SetUp() override {
        std::uniform_real_distribution<float> size(0.0f, 2.0f);
        for (int i = 0; i < 400; ++i) add(random_point(), size(random_));
    }

    btVector3 random_point() {
        std::uniform_real_distribution<float> where(0.0f, 20.0f);
        return btVector3(where(random_), where(random_), where(random_));
    }

    btBroadphaseProxy* add(const btVector3& min, float size) {
        btBroadphaseProxy* proxy = broadphase_.createProxy(min, min + btVector3(size, size * 0.5f, size),
                                                           BOX_SHAPE_PROXYTYPE, nullptr, 1, -1, nullptr);
        proxies_.push_back(proxy);
        return proxy;
    }

    /// The entry, in distance from `from`, of the ray towards `to` into each proxy's box grown by
    /// [-grow_max, -grow_min], as smb::ray_entry defines it, nearest first (ties by unique id).
    std::vector<std::pair<float, int>> expected_hits(const btVector3& from, const btVector3& to, float lambda_max,
                                                     const btVector3& grow_min = btVector3(0, 0, 0),
                                                     const btVector3& grow_max = btVector3(0, 0, 0)) const {
        smb::Ray<float, 3> ray;
        ray.origin = {from.x(), from.y(), from.z()};
        const btVector3 offset = to - from;
        const float length = offset.length();
        const btVector3 unit = length > 0 ? offset / length : btVector3(0, 0, 0);
        ray.direction = {unit.x(), unit.y(), unit.z()};
        ray.max_t = lambda_max;
        std::vector<std::pair<float, int>> hits;
        for (const btBroadphaseProxy* proxy : proxies_) {
            smb::Box<float, 3> box;
            for (int k = 0; k < 3; ++k) {
                box.min[k] = proxy->m_aabbMin[k] - grow_max[k];
                box.max[k] = proxy->m_aabbMax[k] - grow_min[k];
            }
            if (const std::optional<double> t = smb::ray_entry(ray, box)) {
                hits.emplace_back(static_cast<float>(*t), proxy->m_uniqueId);
            }
        }
        std::sort(hits.begin(), hits.end());
        return hits;
    }

    static std::vector<int> ids_of(const std::vector<std::pair<float, int>>& hits) {
        std::vector<int> ids;
        for (const auto& hit : hits) ids.push_back(hit.second);
        return ids;
    }

    Broadphase broadphase_;
    std::vector<btBroadphaseProxy*> proxies_;
    std::mt19937 random_{2024};
};

TEST_F(BulletQueries, RayTestVisitsEveryBoxTheSegmentEntersNearestFirst) {
    std::size_t total = 0;
    for (int i = 0; i < queries; ++i) {
        const btVector3 from = random_point();
        const btVector3 to = i % 10 == 0 ? from : random_point();  // some zero-length segments
        RayRecorder recorder(from.distance(to));
        broadphase_.rayTest(from, to, recorder);
        ASSERT_EQ(recorder.visited, ids_of(expected_hits(from, to, from.distance(to)))) << "query " << i;
        total += recorder.visited.size();
    }
    EXPECT_GT(total, static_cast<std::size_t>(queries / 2));  // the rays do hit
}

TEST_F(BulletQueries, RayTestGrowsTheBoxesBySweptShapesBox) {
    for (int i = 0; i < queries; ++i) {
        const btVector3 from = random_point();
        const btVector3 to = random_point();
        const btVector3 grow_min(-0.5f, -0.25f, -1.0f);
        const btVector3 grow_max(0.5f, 0.75f, 0.0f);
        RayRecorder recorder(from.distance(to));
        broadphase_.rayTest(from, to, recorder, grow_min, grow_max);
        ASSERT_EQ(recorder.visited, ids_of(expected_hits(from, to, from.distance(to), grow_min, grow_max)))
            << "query " << i;
    }
}

TEST_F(BulletQueries, RayTestStopsWhenProcessSaysSoOrTheRayShortens) {
    for (int i = 0; i < queries; ++i) {
        const btVector3 from = random_point();
        const btVector3 to = random_point();
        const float length = from.distance(to);
        const auto hits = expected_hits(from, to, length);
        if (hits.size() < 2) continue;
        RayRecorder stopper(length);
        stopper.on_visit = [&](const btBroadphaseProxy&, RayRecorder& self) { return self.visited.size() < 2; };
        broadphase_.rayTest(from, to, stopper);
        ASSERT_EQ(stopper.visited, std::vector<int>({hits[0].second, hits[1].second}));

        // A callback that found a surface at the first entry: only boxes entered no later follow.
        RayRecorder shortener(length);
        shortener.on_visit = [&](const btBroadphaseProxy&, RayRecorder& self) {
            self.m_lambda_max = std::min(self.m_lambda_max, hits[0].first);
            return true;
        };
        broadphase_.rayTest(from, to, shortener);
        std::vector<int> expected;
        for (const auto& hit : hits) {
            if (hit.first <= hits[0].first) expected.push_back(hit.second);
        }
        ASSERT_EQ(shortener.visited, expected);

        RayRecorder half(length / 2);
        broadphase_.rayTest(from, to, half);
        ASSERT_EQ(half.visited, ids_of(expected_hits(from, to, length / 2)));
    }
}

TEST_F(BulletQueries, AabbTestVisitsEveryOverlappingBox) {
    for (int i = 0; i < queries; ++i) {
        const btVector3 min = random_point();
        const btVector3 max = min + btVector3(3, 1, 2);
        BoxRecorder recorder;
        broadphase_.aabbTest(min, max, recorder);
        btBroadphaseProxy query(min, max, nullptr, 1, -1);
        std::vector<int> expected;
        for (const btBroadphaseProxy* proxy : proxies_) {
            if (smb::test::proxies_overlap(*proxy, query)) expected.push_back(proxy->m_uniqueId);
        }
        std::sort(recorder.visited.begin(), recorder.visited.end());
        std::sort(expected.begin(), expected.end());
        ASSERT_EQ(recorder.visited, expected) << "query " << i;
    }
    BoxRecorder recorder;
    EXPECT_THROW(broadphase_.aabbTest(btVector3(1, 1, 1), btVector3(0, 0, 0), recorder), smb::InvalidBoxError);
}

TEST_F(BulletQueries, CallbacksMayCreateAndDestroyProxies) {
    broadphase_.calculateOverlappingPairs(nullptr);
    for (int i = 0; i < queries / 4; ++i) {
        // Each visit destroys the proxy visited and another one, which the test may yet have
        // reached, and creates one.
        std::vector<int> destroyed;
        auto destroy = [&](btBroadphaseProxy* target) {
            destroyed.push_back(target->m_uniqueId);
            broadphase_.destroyProxy(target, nullptr);
            proxies_.erase(std::find(proxies_.begin(), proxies_.end(), target));
        };
        auto mutate = [&](const btBroadphaseProxy& visited) {
            destroy(const_cast<btBroadphaseProxy*>(&visited));
            if (proxies_.size() > 10) {
                destroy(proxies_[std::uniform_int_distribution<std::size_t>(0, proxies_.size() - 1)(random_)]);
            }
            add(random_point(), 1.0f);
            return true;
        };
        const btVector3 from = random_point();
        const btVector3 to = random_point();
        RayRecorder ray(from.distance(to));
        ray.on_visit = [&](const btBroadphaseProxy& visited, RayRecorder&) {
            for (const int gone : destroyed) EXPECT_NE(visited.m_uniqueId, gone);
            return mutate(visited);
        };
        broadphase_.rayTest(from, to, ray);
        BoxRecorder box;
        box.on_visit = [&](const btBroadphaseProxy& visited) {
            for (const int gone : destroyed) EXPECT_NE(visited.m_uniqueId, gone);
            return mutate(visited);
        };
        const btVector3 min = random_point();
        broadphase_.aabbTest(min, min + btVector3(2, 2, 2), box);
        broadphase_.calculateOverlappingPairs(nullptr);
        ASSERT_EQ(smb::test::cache_pairs(*broadphase_.getOverlappingPairCache()),
                  smb::test::expected_pairs(proxies_, *broadphase_.getOverlappingPairCache()));
    }
}

}  // namespace
