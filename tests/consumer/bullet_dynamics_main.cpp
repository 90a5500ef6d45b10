// SPDX-License-Identifier: MIT
// A consumer of smb::bullet_dynamics: docs/bullet.md's switch in a program that links, a box
// falling onto another one through a btDiscreteDynamicsWorld on smb's broad phase.

#include <btBulletDynamicsCommon.h>
#include <smb/bullet/broadphase.hpp>

#include <iostream>

int main() {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btSequentialImpulseConstraintSolver solver;
    smb::bullet::Broadphase broadphase;  // in place of: btDbvtBroadphase broadphase;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
    world.setGravity(btVector3(0, -10, 0));

    btBoxShape shape(btVector3(1, 1, 1));
    btDefaultMotionState ground_state(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
    btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &ground_state, &shape));
    btVector3 inertia(0, 0, 0);
    shape.calculateLocalInertia(1, inertia);
    btDefaultMotionState falling_state(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
    btRigidBody falling(btRigidBody::btRigidBodyConstructionInfo(1, &falling_state, &shape, inertia));
    world.addRigidBody(&ground);
    world.addRigidBody(&falling);
    for (int step = 0; step < 240; ++step) world.stepSimulation(1.0 / 60, 1);
    const btScalar y = falling.getCenterOfMassPosition().getY();
    world.removeRigidBody(&falling);
    world.removeRigidBody(&ground);
    if (!(y > 0.5 && y < 1.5)) {
        std::cerr << "the falling box should rest on the ground (y about 1), not at y = " << y << "\n";
        return 1;
    }
    std::cout << "smb::bullet_dynamics: the box rests on the ground at y = " << y << "\n";
    return 0;
}
