// SPDX-License-Identifier: MIT
// The proof on a real simulation: a pile steps on btDbvtBroadphase, and a mirror collision world
// on smb::bullet::Broadphase holds the same objects with the same transforms, step by step. After
// every step, smb's pair cache must hold exactly the pairs of objects whose current boxes overlap
// (found here by an independent sweep), and ray casts, convex sweeps and contact tests through
// btCollisionWorld must give the same hits in both worlds. Exit status 1 on the first difference.
//
//   smb_bullet_lockstep --bodies 10000 --steps 300

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <memory>
#include <random>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pile_scene.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

using Serial = std::pair<int, int>;

/// Every pair of objects whose broad-phase boxes overlap (closed) and whose filter bits pass, by
/// user index: a sweep along x, independent of either broad phase.
std::vector<Serial> overlapping_pairs(btCollisionWorld& world) {
    std::vector<const btCollisionObject*> objects;
    for (int i = 0; i < world.getNumCollisionObjects(); ++i) objects.push_back(world.getCollisionObjectArray()[i]);
    std::sort(objects.begin(), objects.end(), [](const btCollisionObject* a, const btCollisionObject* b) {
        return a->getBroadphaseHandle()->m_aabbMin.x() < b->getBroadphaseHandle()->m_aabbMin.x();
    });
    std::vector<Serial> pairs;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const btBroadphaseProxy& a = *objects[i]->getBroadphaseHandle();
        for (std::size_t j = i + 1; j < objects.size(); ++j) {
            const btBroadphaseProxy& b = *objects[j]->getBroadphaseHandle();
            if (b.m_aabbMin.x() > a.m_aabbMax.x()) break;
            bool overlap = true;
            for (int k = 1; k < 3; ++k)
                overlap = overlap && a.m_aabbMin[k] <= b.m_aabbMax[k] && b.m_aabbMin[k] <= a.m_aabbMax[k];
            const bool pass = (a.m_collisionFilterGroup & b.m_collisionFilterMask) != 0 &&
                              (b.m_collisionFilterGroup & a.m_collisionFilterMask) != 0;
            if (overlap && pass) pairs.push_back(std::minmax(objects[i]->getUserIndex(), objects[j]->getUserIndex()));
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

std::vector<Serial> cache_pairs(btOverlappingPairCache& cache) {
    std::vector<Serial> pairs;
    const btBroadphasePairArray& array = cache.getOverlappingPairArray();
    for (int i = 0; i < array.size(); ++i) {
        const auto* a = static_cast<const btCollisionObject*>(array[i].m_pProxy0->m_clientObject);
        const auto* b = static_cast<const btCollisionObject*>(array[i].m_pProxy1->m_clientObject);
        pairs.push_back(std::minmax(a->getUserIndex(), b->getUserIndex()));
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

/// The objects of a simulated world, mirrored into a collision world of their own.
class Mirror {
public:
    explicit Mirror(btBroadphaseInterface& broadphase)
        : dispatcher_(&configuration_), world_(&dispatcher_, &broadphase, &configuration_) {}
    ~Mirror() {
        for (auto& [source, copy] : copies_) world_.removeCollisionObject(copy.get());
    }
    Mirror(const Mirror&) = delete;
    Mirror& operator=(const Mirror&) = delete;

    /// Adds, removes and moves objects to match `source`, gives them the boxes they have there,
    /// then finds the pairs.
    void follow(btCollisionWorld& source) {
        // By name, not by address: a body taken out and one dropped in may share an address.
        std::unordered_map<int, bool> present;
        for (int i = 0; i < source.getNumCollisionObjects(); ++i) {
            btCollisionObject* original = source.getCollisionObjectArray()[i];
            present[original->getUserIndex()] = true;
            auto& copy = copies_[original->getUserIndex()];
            if (!copy) {
                copy = std::make_unique<btCollisionObject>();
                copy->setCollisionShape(original->getCollisionShape());
                copy->setCollisionFlags(original->getCollisionFlags());
                copy->setUserIndex(original->getUserIndex());
                copy->setWorldTransform(original->getWorldTransform());
                const btBroadphaseProxy& handle = *original->getBroadphaseHandle();
                world_.addCollisionObject(copy.get(), handle.m_collisionFilterGroup, handle.m_collisionFilterMask);
            }
            copy->setWorldTransform(original->getWorldTransform());
            // The boxes the source's broad phase holds, not boxes worked out again: a rigid
            // body's box covers its predicted motion too, which a plain object's does not.
            const btBroadphaseProxy& handle = *original->getBroadphaseHandle();
            world_.getBroadphase()->setAabb(copy->getBroadphaseHandle(), handle.m_aabbMin, handle.m_aabbMax,
                                            &dispatcher_);
        }
        for (auto it = copies_.begin(); it != copies_.end();) {
            if (present.contains(it->first)) {
                ++it;
                continue;
            }
            world_.removeCollisionObject(it->second.get());
            it = copies_.erase(it);
        }
        world_.computeOverlappingPairs();
    }

    btCollisionWorld& world() { return world_; }

private:
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_;
    btCollisionWorld world_;
    std::unordered_map<int, std::unique_ptr<btCollisionObject>> copies_;
};

/// Every object a ray hits, with the fraction of the way to it. (Bullet's AllHitsRayResultCallback
/// lowers its bound with each hit, so what it reports depends on the order the broad phase visits
/// the objects in; this one keeps the whole ray.)
struct EveryHit : btCollisionWorld::RayResultCallback {
    btScalar addSingleResult(btCollisionWorld::LocalRayResult& result, bool) override {
        hits.emplace_back(result.m_collisionObject->getUserIndex(), result.m_hitFraction);
        return m_closestHitFraction;
    }
    std::vector<std::tuple<int, float>> hits;
};

std::vector<std::tuple<int, float>> ray_hits(btCollisionWorld& world, const btVector3& from, const btVector3& to) {
    EveryHit every;
    world.rayTest(from, to, every);
    std::sort(every.hits.begin(), every.hits.end());
    return every.hits;
}

/// The fraction of the way a sphere swept from `from` to `to` goes before it first touches an
/// object (1: it touches none). Which object it touches first is left out: where several are
/// touched at the same fraction (a layer of boxes), Bullet keeps the first one it visits, and the
/// broad phases visit in different orders.
float sweep_fraction(btCollisionWorld& world, const btConvexShape& shape, const btVector3& from, const btVector3& to) {
    btCollisionWorld::ClosestConvexResultCallback closest(from, to);
    world.convexSweepTest(&shape, btTransform(btQuaternion::getIdentity(), from),
                          btTransform(btQuaternion::getIdentity(), to), closest);
    return closest.m_closestHitFraction;
}

/// The objects a probe touches or penetrates (contact distance <= 0), and those it merely comes
/// near (a positive distance below Bullet's contact threshold). Bullet reports the latter only
/// when the broad phase offers the object, which its fattened boxes do more often than smb's
/// exact ones: only the former are the same by right.
struct ContactNames : btCollisionWorld::ContactResultCallback {
    btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* a, int, int,
                             const btCollisionObjectWrapper* b, int, int) override {
        const Serial name =
            std::minmax(a->getCollisionObject()->getUserIndex(), b->getCollisionObject()->getUserIndex());
        (point.getDistance() <= 0 ? touching : near).push_back(name);
        return 0;
    }
    std::vector<Serial> touching;
    std::vector<Serial> near;
};

void sort_unique(std::vector<Serial>& names) {
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
}

/// The objects the probe touches, and whether every object it comes near (or touches) in `world`
/// is one it comes near (or touches) in `wider`.
ContactNames contacts(btCollisionWorld& world, btCollisionObject& probe) {
    ContactNames names;
    world.contactTest(&probe, names);
    sort_unique(names.touching);
    sort_unique(names.near);
    return names;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"A Bullet pile on btDbvtBroadphase with a mirror on smb's broad phase, compared at every step"};
    app.option_defaults()->always_capture_default();  // --help shows each option's default
    smb::examples::PileSettings settings;
    int steps = 300;
    int queries = 20;
    app.add_option("--bodies", settings.bodies, "boxes and spheres poured")->check(CLI::Range(1, 10'000'000));
    app.add_option("--steps", steps, "steps of 1/60 s")->check(CLI::NonNegativeNumber);
    app.add_option("--queries", queries, "ray casts, convex sweeps and contact tests per step")
        ->check(CLI::NonNegativeNumber);
    CLI11_PARSE(app, argc, argv);

    btDbvtBroadphase dbvt;
    smb::examples::PileScene scene(dbvt, settings);
    smb::bullet::Broadphase broadphase;
    Mirror mirror(broadphase);
    btSphereShape probe_shape(0.7f);
    btCollisionObject probe;
    probe.setCollisionShape(&probe_shape);
    std::mt19937 random(7);
    int next_serial = 0;
    std::size_t pairs_checked = 0;
    std::size_t dbvt_pairs = 0;
    std::size_t hits_compared = 0;
    std::size_t near_only_dbvt = 0;
    std::size_t hits_outside_box = 0;
    std::vector<const btCollisionObject*> objects_by_name;
    auto last_report = std::chrono::steady_clock::now();
    for (int step = 0; step <= steps; ++step) {
        if (step > 0) scene.step();
        btCollisionWorld& source = scene.world();
        // A step leaves the broad phase with the boxes from before the bodies moved; queries and
        // the comparison want the boxes where they are now.
        source.updateAabbs();
        for (int i = 0; i < source.getNumCollisionObjects(); ++i) {
            btCollisionObject* object = source.getCollisionObjectArray()[i];
            if (object->getUserIndex() < 0) object->setUserIndex(next_serial++);
            objects_by_name.resize(static_cast<std::size_t>(next_serial));
            objects_by_name[static_cast<std::size_t>(object->getUserIndex())] = object;
        }
        mirror.follow(source);
        const std::vector<Serial> exact = overlapping_pairs(source);
        if (const auto held = cache_pairs(*broadphase.getOverlappingPairCache()); held != exact) {
            fmt::print(stderr, "step {}: smb's cache differs from the {} overlapping pairs\n", step, exact.size());
            std::vector<Serial> missing;
            std::vector<Serial> extra;
            std::set_difference(exact.begin(), exact.end(), held.begin(), held.end(), std::back_inserter(missing));
            std::set_difference(held.begin(), held.end(), exact.begin(), exact.end(), std::back_inserter(extra));
            for (const auto& [a, b] : missing) fmt::print(stderr, "  missing {} {}\n", a, b);
            for (const auto& [a, b] : extra) fmt::print(stderr, "  extra {} {}\n", a, b);
            return 1;
        }
        pairs_checked += exact.size();
        dbvt_pairs += static_cast<std::size_t>(dbvt.getOverlappingPairCache()->getNumOverlappingPairs());

        const float w = scene.half_width();
        std::uniform_real_distribution<float> across(-w, w);
        std::uniform_real_distribution<float> up(0.0f, 8.0f);
        for (int q = 0; q < queries; ++q) {
            const btVector3 from(across(random), up(random) + 4, across(random));
            const btVector3 to(across(random), up(random) - 2, across(random));
            const auto expected = ray_hits(source, from, to);
            // smb must offer every object whose box the ray enters; Bullet's narrow phase then
            // decides, and its subsimplex ray cast sometimes reports a hit at a point outside the
            // object's box (on an object that btDbvtBroadphase's fattened boxes offered).
            const auto mirrored = ray_hits(mirror.world(), from, to);
            std::vector<std::tuple<int, float>> within;
            for (const auto& [name, fraction] : expected) {
                const btVector3 point = from.lerp(to, fraction);
                const btBroadphaseProxy& box = *objects_by_name[static_cast<std::size_t>(name)]->getBroadphaseHandle();
                const btVector3 slack(1e-3f, 1e-3f, 1e-3f);
                if (TestPointAgainstAabb2(box.m_aabbMin - slack, box.m_aabbMax + slack, point)) {
                    within.emplace_back(name, fraction);
                } else {
                    ++hits_outside_box;
                }
            }
            const bool offered = std::includes(expected.begin(), expected.end(), mirrored.begin(), mirrored.end()) &&
                                 std::includes(mirrored.begin(), mirrored.end(), within.begin(), within.end());
            if (!offered) {
                fmt::print(stderr, "step {}: a ray cast differs: {} hits on btDbvtBroadphase, {} on smb\n", step,
                           expected.size(), mirrored.size());
                return 1;
            }
            const float swept = sweep_fraction(source, probe_shape, from, to);
            if (sweep_fraction(mirror.world(), probe_shape, from, to) != swept) {
                fmt::print(stderr, "step {}: a convex sweep differs (btDbvtBroadphase: {})\n", step, swept);
                return 1;
            }
            probe.setWorldTransform(btTransform(btQuaternion::getIdentity(), to));
            const ContactNames dbvt_contacts = contacts(source, probe);
            const ContactNames smb_contacts = contacts(mirror.world(), probe);
            const bool near_included = std::includes(dbvt_contacts.near.begin(), dbvt_contacts.near.end(),
                                                     smb_contacts.near.begin(), smb_contacts.near.end());
            if (smb_contacts.touching != dbvt_contacts.touching || !near_included) {
                fmt::print(stderr,
                           "step {}: a contact test differs: {} objects touched on btDbvtBroadphase, {} on smb\n", step,
                           dbvt_contacts.touching.size(), smb_contacts.touching.size());
                return 1;
            }
            hits_compared += expected.size() + dbvt_contacts.touching.size();
            near_only_dbvt += dbvt_contacts.near.size() - smb_contacts.near.size();
        }
        // A run takes tens of seconds: say how far it got, on standard error, about every 2 s.
        if (const auto now = std::chrono::steady_clock::now(); now - last_report >= std::chrono::seconds(2)) {
            fmt::print(stderr, "smb_bullet_lockstep: step {} of {}, {} pairs checked so far\n", step, steps,
                       pairs_checked);
            last_report = now;
        }
    }
    const smb::examples::PileMeasure measure = scene.measure();
    fmt::print(
        "{} steps of {} bodies: smb's cache held exactly the {} overlapping pairs of every step "
        "(btDbvtBroadphase's held {}, fattened); {} ray, sweep and contact hits agreed ({} objects near a probe "
        "but not touching it, and {} ray hits outside the object's box, were reported on btDbvtBroadphase "
        "alone); mean height {:.3f}\n",
        steps, settings.bodies, pairs_checked, dbvt_pairs, hits_compared, near_only_dbvt, hits_outside_box,
        measure.mean_height);
    return 0;
}
