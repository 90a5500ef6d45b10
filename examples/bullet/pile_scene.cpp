// SPDX-License-Identifier: MIT
#include "pile_scene.hpp"

#include <algorithm>
#include <cmath>

namespace smb::examples {

namespace {

constexpr float spacing = 1.2f;  // between the centres of bodies of size 1 poured in a lattice
constexpr float time_step = 1.0f / 60.0f;

}  // namespace

PileScene::PileScene(btBroadphaseInterface& broadphase, const PileSettings& settings)
    : settings_(settings),
      dispatcher_(&configuration_),
      world_(&dispatcher_, &broadphase, &solver_, &configuration_),
      box_shape_(btVector3(0.5f, 0.5f, 0.5f)),
      sphere_shape_(0.5f),
      plough_shape_(btVector3(1.0f, 2.0f, 6.0f)),
      random_(settings.seed) {
    world_.setGravity(btVector3(0, -10, 0));
    // A floor about three times the area the bodies cover lying in one layer: the pile settles a
    // few layers deep.
    const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(settings.bodies) / 4.0)));
    half_width_ = static_cast<float>(side) * spacing * 0.5f + 1.0f;
    floor_shape_ = std::make_unique<btBoxShape>(btVector3(half_width_ + 1, 1, half_width_ + 1));
    wall_shape_x_ = std::make_unique<btBoxShape>(btVector3(0.5f, 8, half_width_ + 1));
    wall_shape_z_ = std::make_unique<btBoxShape>(btVector3(half_width_ + 1, 8, 0.5f));
    owned_.add(world_, *floor_shape_, 0, btVector3(0, -1, 0));
    owned_.add(world_, *wall_shape_x_, 0, btVector3(-half_width_ - 0.5f, 8, 0));
    owned_.add(world_, *wall_shape_x_, 0, btVector3(half_width_ + 0.5f, 8, 0));
    owned_.add(world_, *wall_shape_z_, 0, btVector3(0, 8, -half_width_ - 0.5f));
    owned_.add(world_, *wall_shape_z_, 0, btVector3(0, 8, half_width_ + 0.5f));
    plough_ = &owned_.add(world_, plough_shape_, 0, btVector3(-half_width_ + 1.5f, 2, 0));
    plough_->setCollisionFlags(plough_->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
    if (settings.keep_plough_awake) plough_->setActivationState(DISABLE_DEACTIVATION);
    fixed_bodies_ = owned_.bodies.size();

    std::uniform_real_distribution<float> jitter(-0.05f, 0.05f);
    for (std::size_t i = 0; i < settings.bodies; ++i) {
        const std::size_t layer = i / (side * side);
        const std::size_t row = (i / side) % side;
        const std::size_t column = i % side;
        const float x = (static_cast<float>(column) + 0.5f) * spacing - static_cast<float>(side) * spacing * 0.5f;
        const float z = (static_cast<float>(row) + 0.5f) * spacing - static_cast<float>(side) * spacing * 0.5f;
        drop_body(btVector3(x + jitter(random_), 1.0f + static_cast<float>(layer) * spacing, z + jitter(random_)));
    }
}

PileScene::~PileScene() { owned_.remove_all(world_); }

void PileScene::drop_body(const btVector3& origin) {
    // Two boxes for every sphere.
    const bool sphere = settings_.spheres && owned_.bodies.size() % 3 == 0;
    btRigidBody& body =
        owned_.add(world_, sphere ? static_cast<btCollisionShape&>(sphere_shape_) : box_shape_, 1.0f, origin);
    body.setDamping(settings_.linear_damping, settings_.angular_damping);
    body.setSleepingThresholds(settings_.linear_sleeping_threshold, settings_.angular_sleeping_threshold);
}

void PileScene::step() {
    if (settings_.plough) {
        btTransform where;
        plough_->getMotionState()->getWorldTransform(where);
        const float x = where.getOrigin().x() + plough_speed_;
        if (std::abs(x) > half_width_ - 1.5f) plough_speed_ = -plough_speed_;
        where.setOrigin(btVector3(x, where.getOrigin().y(), where.getOrigin().z()));
        plough_->getMotionState()->setWorldTransform(where);
    }
    if (settings_.churn_every > 0 && steps_ > 0 && steps_ % settings_.churn_every == 0) {
        std::uniform_real_distribution<float> across(-half_width_ + 1, half_width_ - 1);
        for (std::size_t i = 0; i < settings_.churn && owned_.bodies.size() > fixed_bodies_; ++i) {
            std::uniform_int_distribution<std::size_t> pick(fixed_bodies_, owned_.bodies.size() - 1);
            owned_.remove(world_, pick(random_));
        }
        for (std::size_t i = 0; i < settings_.churn; ++i) {
            drop_body(btVector3(across(random_), 14.0f + static_cast<float>(i % 4) * spacing, across(random_)));
        }
    }
    world_.stepSimulation(time_step, 1, time_step);
    ++steps_;
}

PileMeasure PileScene::measure() const {
    PileMeasure measure;
    std::size_t moving = 0;
    for (std::size_t i = fixed_bodies_; i < owned_.bodies.size(); ++i) {
        const btRigidBody& body = *owned_.bodies[i];
        measure.mean_height += body.getCenterOfMassPosition().y();
        const btVector3 spin = body.getAngularVelocity();
        const btVector3 inertia = body.getLocalInertia();
        measure.kinetic_energy +=
            0.5 * body.getLinearVelocity().length2() / body.getInvMass() + 0.5 * (spin * spin).dot(inertia);
        ++moving;
        if (body.isActive()) ++measure.awake;
        if (body.getActivationState() == ISLAND_SLEEPING) ++measure.asleep;
    }
    if (moving > 0) measure.mean_height /= static_cast<double>(moving);
    const int manifolds = dispatcher_.getNumManifolds();
    measure.manifolds = static_cast<std::size_t>(manifolds);
    for (int i = 0; i < manifolds; ++i) {
        measure.contacts += static_cast<std::size_t>(
            const_cast<btCollisionDispatcher&>(dispatcher_).getManifoldByIndexInternal(i)->getNumContacts());
    }
    return measure;
}

}  // namespace smb::examples
