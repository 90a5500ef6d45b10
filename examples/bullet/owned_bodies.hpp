// SPDX-License-Identifier: MIT
#pragma once
// Rigid bodies a scene owns with their motion states, added to and taken out of a Bullet world
// together: the pile scene (pile_scene.hpp) and the test that steps a world on smb
// (tests/bullet/test_bullet_world.cpp) both keep their bodies this way.

#include <btBulletDynamicsCommon.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace smb::examples {

struct OwnedBodies {
    std::vector<std::unique_ptr<btDefaultMotionState>> motions;
    std::vector<std::unique_ptr<btRigidBody>> bodies;

    /// A body of `shape` at `origin`, unrotated, added to `world`; static where `mass` is 0.
    btRigidBody& add(btDiscreteDynamicsWorld& world, btCollisionShape& shape, float mass, const btVector3& origin) {
        btVector3 inertia(0, 0, 0);
        if (mass > 0) shape.calculateLocalInertia(mass, inertia);
        motions.push_back(std::make_unique<btDefaultMotionState>(btTransform(btQuaternion::getIdentity(), origin)));
        bodies.push_back(std::make_unique<btRigidBody>(
            btRigidBody::btRigidBodyConstructionInfo(mass, motions.back().get(), &shape, inertia)));
        world.addRigidBody(bodies.back().get());
        return *bodies.back();
    }

    /// Takes body `index` out of `world` and destroys it; the last body takes its place.
    void remove(btDiscreteDynamicsWorld& world, std::size_t index) {
        world.removeRigidBody(bodies[index].get());
        bodies[index] = std::move(bodies.back());
        bodies.pop_back();
        motions[index] = std::move(motions.back());
        motions.pop_back();
    }

    /// Takes every body out of `world` (before the world, or the shapes, go).
    void remove_all(btDiscreteDynamicsWorld& world) {
        for (auto& body : bodies) world.removeRigidBody(body.get());
    }
};

}  // namespace smb::examples
