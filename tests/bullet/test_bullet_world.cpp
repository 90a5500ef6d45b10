// SPDX-License-Identifier: MIT
// smb::bullet::Broadphase inside a btDiscreteDynamicsWorld: a pile of boxes and spheres poured on
// a static floor, a kinematic body pushing through, bodies added and removed. After every step
// the cache must hold exactly the overlapping pairs of the objects' boxes, and every contact
// manifold must belong to a pair the cache holds (removed pairs freed theirs).

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <set>
#include <vector>

#include "bullet/cache_reference.hpp"
#include "owned_bodies.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

#if defined(SMB_TEST_REDUCED)
constexpr int bodies = 120;
constexpr int steps = 60;
#else
constexpr int bodies = 400;
constexpr int steps = 150;
#endif

class PileWorld {
public:
    PileWorld()
        : dispatcher_(&configuration_),
          world_(&dispatcher_, &broadphase_, &solver_, &configuration_),
          floor_shape_(btVector3(20, 1, 20)),
          box_shape_(btVector3(0.5f, 0.5f, 0.5f)),
          sphere_shape_(0.5f),
          pusher_shape_(btVector3(1, 2, 6)) {
        world_.setGravity(btVector3(0, -10, 0));
        add_body(floor_shape_, 0, btVector3(0, -1, 0));
        btRigidBody& pusher = add_body(pusher_shape_, 0, btVector3(-15, 2, 0));
        pusher.setCollisionFlags(pusher.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
        pusher.setActivationState(DISABLE_DEACTIVATION);
        pusher_ = &pusher;
        for (int i = 0; i < bodies; ++i) drop_one();
    }

    ~PileWorld() { owned_.remove_all(world_); }
    PileWorld(const PileWorld&) = delete;
    PileWorld& operator=(const PileWorld&) = delete;

    void drop_one() {
        std::uniform_real_distribution<float> across(-6.0f, 6.0f);
        std::uniform_real_distribution<float> up(1.0f, 14.0f);
        const bool sphere = owned_.bodies.size() % 3 == 0;
        add_body(sphere ? static_cast<btCollisionShape&>(sphere_shape_) : box_shape_, 1,
                 btVector3(across(random_), up(random_), across(random_)));
    }

    void remove_one() {
        std::uniform_int_distribution<std::size_t> pick(2, owned_.bodies.size() - 1);  // not the floor or pusher
        owned_.remove(world_, pick(random_));
    }

    void step(int index) {
        btTransform where;
        pusher_->getMotionState()->getWorldTransform(where);
        where.setOrigin(where.getOrigin() + btVector3(0.2f, 0, 0));
        pusher_->getMotionState()->setWorldTransform(where);
        if (index % 10 == 5) {
            remove_one();
            drop_one();
            drop_one();
        }
        world_.stepSimulation(1.0f / 60.0f, 1, 1.0f / 60.0f);
    }

    [[nodiscard]] std::vector<btBroadphaseProxy*> proxies() const {
        std::vector<btBroadphaseProxy*> out;
        for (const auto& body : owned_.bodies) out.push_back(body->getBroadphaseHandle());
        return out;
    }

    smb::bullet::Broadphase broadphase_;
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_;

private:
    btRigidBody& add_body(btCollisionShape& shape, float mass, const btVector3& origin) {
        return owned_.add(world_, shape, mass, origin);
    }

    btBoxShape floor_shape_;
    btBoxShape box_shape_;
    btSphereShape sphere_shape_;
    btBoxShape pusher_shape_;
    smb::examples::OwnedBodies owned_;
    btRigidBody* pusher_ = nullptr;
    std::mt19937 random_{99};
};

TEST(BulletWorld, EveryStepsCacheIsExactAndEveryManifoldHasItsPair) {
    auto scene = std::make_unique<PileWorld>();
    std::size_t most_manifolds = 0;
    for (int step = 0; step < steps; ++step) {
        scene->step(step);
        btOverlappingPairCache& cache = *scene->broadphase_.getOverlappingPairCache();
        const auto held = smb::test::cache_pairs(cache);
        ASSERT_EQ(held, smb::test::expected_pairs(scene->proxies(), cache)) << "at step " << step;

        const std::set<smb::test::UidPair> pairs(held.begin(), held.end());
        btDispatcher& dispatcher = scene->dispatcher_;
        for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
            const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(i);
            const auto pair = smb::test::uid_pair(*manifold.getBody0()->getBroadphaseHandle(),
                                                  *manifold.getBody1()->getBroadphaseHandle());
            ASSERT_TRUE(pairs.contains(pair)) << "a manifold outlived its pair at step " << step;
        }
        most_manifolds = std::max(most_manifolds, static_cast<std::size_t>(dispatcher.getNumManifolds()));
    }
    EXPECT_GT(most_manifolds, static_cast<std::size_t>(bodies / 2));  // the pile did touch
}

}  // namespace
