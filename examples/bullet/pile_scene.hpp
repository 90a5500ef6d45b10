// SPDX-License-Identifier: MIT
#pragma once
// A Bullet rigid-body scene for the broad phase to work on: boxes and spheres poured onto a
// static floor between static walls, a kinematic plough pushing through them, and bodies taken
// out and dropped in again as it runs. The broad phase is the caller's: the scene runs the same
// with btDbvtBroadphase, btAxisSweep3 or smb::bullet::Broadphase.

#include <btBulletDynamicsCommon.h>

#include <cstddef>
#include <memory>
#include <random>
#include <vector>

#include "owned_bodies.hpp"

namespace smb::examples {

struct PileSettings {
    std::size_t bodies = 2000;
    unsigned seed = 1;
    /// Every `churn_every` steps, `churn` bodies are taken out and as many dropped in from above
    /// (0: never).
    int churn_every = 25;
    std::size_t churn = 20;
    /// Every third body poured is a sphere while true; all are boxes while false. With spheres
    /// the settled pile keeps creeping (some body somewhere always moves) and Bullet keeps its
    /// one island awake; boxes alone, poured in columns, come to rest and Bullet puts them to
    /// sleep (with the damping and thresholds of the step benchmark's damped scenes).
    bool spheres = true;
    /// The plough moves only while true.
    bool plough = true;
    /// Bullet never deactivates the plough while true. A kinematic body Bullet keeps awake wakes
    /// every body touching it at every step, so a pile with the plough parked in it cannot sleep.
    bool keep_plough_awake = true;
    /// Given to every dynamic body through btRigidBody::setDamping and setSleepingThresholds; the
    /// defaults are Bullet's own.
    float linear_damping = 0;
    float angular_damping = 0;
    float linear_sleeping_threshold = 0.8f;
    float angular_sleeping_threshold = 1.0f;
};

/// What the pile looks like at one instant.
struct PileMeasure {
    double mean_height = 0;    ///< of the dynamic bodies' centres
    std::size_t contacts = 0;  ///< contact points in every manifold
    std::size_t manifolds = 0;
    double kinetic_energy = 0;  ///< translational and rotational, of the dynamic bodies
    std::size_t awake = 0;      ///< dynamic bodies Bullet has not put to sleep
    std::size_t asleep = 0;     ///< dynamic bodies whose island Bullet put to sleep
};

class PileScene {
public:
    PileScene(btBroadphaseInterface& broadphase, const PileSettings& settings);
    ~PileScene();
    PileScene(const PileScene&) = delete;
    PileScene& operator=(const PileScene&) = delete;

    /// Moves the plough, takes out and drops in bodies when it is time, and steps the world by
    /// 1/60 s.
    void step();
    [[nodiscard]] PileMeasure measure() const;

    [[nodiscard]] btDiscreteDynamicsWorld& world() { return world_; }
    [[nodiscard]] btCollisionDispatcher& dispatcher() { return dispatcher_; }
    [[nodiscard]] int steps_done() const { return steps_; }
    /// Half the width of the space between the walls.
    [[nodiscard]] float half_width() const { return half_width_; }

private:
    void drop_body(const btVector3& origin);

    PileSettings settings_;
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_;
    btBoxShape box_shape_;
    btSphereShape sphere_shape_;
    std::unique_ptr<btBoxShape> floor_shape_;
    std::unique_ptr<btBoxShape> wall_shape_x_;
    std::unique_ptr<btBoxShape> wall_shape_z_;
    btBoxShape plough_shape_;
    OwnedBodies owned_;
    std::size_t fixed_bodies_ = 0;  ///< the first bodies: floor, walls, plough
    btRigidBody* plough_ = nullptr;
    float half_width_ = 0;
    float plough_speed_ = 0.1f;
    int steps_ = 0;
    std::mt19937 random_;
};

}  // namespace smb::examples
