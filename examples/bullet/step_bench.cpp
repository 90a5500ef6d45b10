// SPDX-License-Identifier: MIT
// Speed of a Bullet pile on each broad phase: the whole stepSimulation, and the broad phase's part
// of it (calculateOverlappingPairs, and the setAabb calls btCollisionWorld makes for every object
// at every step), in four scenes: an avalanche (bodies pouring down, a plough pushing through,
// bodies taken out and dropped in), the settled pile with Bullet's default sleeping thresholds
// (Bullet keeps it awake), the settled pile with damping and the sleeping thresholds of Bullet's
// demos (the pile keeps creeping and Bullet keeps it awake all the same), and a pile of boxes
// alone with that damping, which Bullet puts to sleep (`asleep` counts the bodies Bullet put to
// sleep, by its own deactivation: nothing here sets a body's activation state). One CSV row per
// broad phase and scene, the first steps apart from the steady state.
//
//   smb_bullet_step_bench --bodies 10000 --broadphase smb,dbvt,sap

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "pile_scene.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// Forwards every call to the broad phase it wraps, timing the calls that make up the broad
/// phase's work in a step. btCollisionWorld sets every object's box at every step, each a call
/// of well under a microsecond: a clock read around each would weigh as much as the calls. They
/// are gathered instead and made together, timed as one, just before calculateOverlappingPairs,
/// or before any other call that could see them; between updateAabbs and the detection
/// btCollisionWorld calls nothing else on the broad phase.
class TimedBroadphase : public btBroadphaseInterface {
public:
    explicit TimedBroadphase(std::unique_ptr<btBroadphaseInterface> inner) : inner_(std::move(inner)) {}

    btBroadphaseProxy* createProxy(const btVector3& min, const btVector3& max, int shape, void* user, int group,
                                   int mask, btDispatcher* dispatcher) override {
        flush_boxes(dispatcher);
        const auto start = Clock::now();
        btBroadphaseProxy* proxy = inner_->createProxy(min, max, shape, user, group, mask, dispatcher);
        broad_ms += ms_since(start);
        return proxy;
    }
    void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override {
        flush_boxes(dispatcher);
        const auto start = Clock::now();
        inner_->destroyProxy(proxy, dispatcher);
        broad_ms += ms_since(start);
    }
    void setAabb(btBroadphaseProxy* proxy, const btVector3& min, const btVector3& max,
                 btDispatcher* dispatcher) override {
        pending_.push_back(PendingBox{proxy, min, max});
        pending_dispatcher_ = dispatcher;
    }
    void getAabb(btBroadphaseProxy* proxy, btVector3& min, btVector3& max) const override {
        flush_boxes(pending_dispatcher_);
        inner_->getAabb(proxy, min, max);
    }
    void rayTest(const btVector3& from, const btVector3& to, btBroadphaseRayCallback& callback, const btVector3& min,
                 const btVector3& max) override {
        flush_boxes(pending_dispatcher_);
        inner_->rayTest(from, to, callback, min, max);
    }
    void aabbTest(const btVector3& min, const btVector3& max, btBroadphaseAabbCallback& callback) override {
        flush_boxes(pending_dispatcher_);
        inner_->aabbTest(min, max, callback);
    }
    void calculateOverlappingPairs(btDispatcher* dispatcher) override {
        flush_boxes(dispatcher);
        const auto start = Clock::now();
        inner_->calculateOverlappingPairs(dispatcher);
        broad_ms += ms_since(start);
    }
    btOverlappingPairCache* getOverlappingPairCache() override { return inner_->getOverlappingPairCache(); }
    const btOverlappingPairCache* getOverlappingPairCache() const override {
        return static_cast<const btBroadphaseInterface&>(*inner_).getOverlappingPairCache();
    }
    void getBroadphaseAabb(btVector3& min, btVector3& max) const override {
        flush_boxes(pending_dispatcher_);
        inner_->getBroadphaseAabb(min, max);
    }
    void resetPool(btDispatcher* dispatcher) override {
        flush_boxes(dispatcher);
        inner_->resetPool(dispatcher);
    }
    void printStats() override { inner_->printStats(); }

    mutable double broad_ms = 0;

    /// Boxes smb's last detection found oversized (spanning more than two segments on some
    /// level, checked apart from the cells); empty for Bullet's broad phases.
    [[nodiscard]] std::string oversized() const {
        const auto* smb_broadphase = dynamic_cast<const smb::bullet::Broadphase*>(inner_.get());
        return smb_broadphase == nullptr ? std::string()
                                         : std::to_string(smb_broadphase->world().last_profile().oversized_boxes);
    }

private:
    struct PendingBox {
        btBroadphaseProxy* proxy;
        btVector3 min;
        btVector3 max;
    };

    /// Makes the gathered setAabb calls, in the order they came.
    void flush_boxes(btDispatcher* dispatcher) const {
        if (pending_.empty()) return;
        const auto start = Clock::now();
        for (const PendingBox& box : pending_) inner_->setAabb(box.proxy, box.min, box.max, dispatcher);
        broad_ms += ms_since(start);
        pending_.clear();
    }

    std::unique_ptr<btBroadphaseInterface> inner_;
    // Mutable: the const calls that read boxes make the gathered calls first.
    mutable std::vector<PendingBox> pending_;
    btDispatcher* pending_dispatcher_ = nullptr;
};

/// smb's skin (smb::bullet::Broadphase's third argument).
float g_skin = smb::bullet::Broadphase::default_skin;

std::unique_ptr<btBroadphaseInterface> make_broadphase(const std::string& name, std::size_t bodies) {
    if (name == "smb") {
        smb::WorldSettings settings;
        settings.profile = true;  // for oversized()
        return std::make_unique<smb::bullet::Broadphase>(settings, nullptr, g_skin);
    }
    if (name == "dbvt") return std::make_unique<btDbvtBroadphase>();
    // Sweep and prune needs bounds: those of the pile with room to spare.
    const float reach = static_cast<float>(std::sqrt(static_cast<double>(bodies))) * 0.7f + 20.0f;
    const btVector3 min(-reach, -20, -reach);
    const btVector3 max(reach, 200, reach);
    if (bodies + 64 < 16384) return std::make_unique<btAxisSweep3>(min, max, static_cast<unsigned short>(bodies + 64));
    return std::make_unique<bt32BitAxisSweep3>(min, max, static_cast<unsigned>(bodies + 64));
}

struct Window {
    double step_ms = 0;
    double broad_ms = 0;
    int steps = 0;
};

/// Steps the scene `steps` times; the first `first` steps go to one window, the rest to another.
void run(smb::examples::PileScene& scene, TimedBroadphase& timed, int steps, int first, Window& head, Window& tail) {
    for (int i = 0; i < steps; ++i) {
        Window& window = i < first ? head : tail;
        timed.broad_ms = 0;
        const auto start = Clock::now();
        scene.step();
        window.step_ms += ms_since(start);
        window.broad_ms += timed.broad_ms;
        ++window.steps;
    }
}

void print_row(const std::string& name, std::size_t bodies, const char* scene, const char* part, const Window& w,
               const smb::examples::PileScene& pile, const TimedBroadphase& timed) {
    const smb::examples::PileMeasure measure = pile.measure();
    fmt::print("{},{},{},{},{},{:.3f},{:.3f},{},{:.3f},{},{},{}\n", name, bodies, scene, part, w.steps,
               w.steps > 0 ? w.step_ms / w.steps : 0.0, w.steps > 0 ? w.broad_ms / w.steps : 0.0, measure.manifolds,
               measure.mean_height, measure.awake, measure.asleep, timed.oversized());
}

/// Lets the pile settle for `settle_steps` untimed steps, then times `rest_steps` steps.
void run_rest(const std::string& name, std::size_t bodies, const char* scene_name,
              const smb::examples::PileSettings& settings, int settle_steps, int rest_steps) {
    TimedBroadphase timed(make_broadphase(name, bodies));
    smb::examples::PileScene scene(timed, settings);
    Window ignored;
    Window settling;
    run(scene, timed, settle_steps, settle_steps, ignored, settling);
    Window head;
    Window tail;
    run(scene, timed, rest_steps, 0, head, tail);
    print_row(name, bodies, scene_name, "steady", tail, scene, timed);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"stepSimulation and broad-phase time of a Bullet pile on smb and Bullet's broad phases"};
    app.option_defaults()->always_capture_default();  // --help shows each option's default
    std::size_t bodies = 10000;
    int motion_steps = 150;
    int settle_steps = 400;
    int damped_settle_steps = 450;
    int rest_steps = 50;
    int first = 10;
    std::vector<std::string> names{"smb", "dbvt", "sap"};
    std::vector<std::string> scenes{"avalanche", "rest", "damped", "asleep"};
    app.add_option("--bodies", bodies)->check(CLI::Range(1, 10'000'000));
    app.add_option("--motion-steps", motion_steps, "steps of the avalanche timed")->check(CLI::PositiveNumber);
    app.add_option("--settle-steps", settle_steps, "untimed steps for the pile to come to rest")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--damped-settle-steps", damped_settle_steps,
                   "untimed steps for the damped piles to come to rest (and the boxes to fall asleep)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--rest-steps", rest_steps, "steps of the settled pile timed")->check(CLI::NonNegativeNumber);
    app.add_option("--first", first, "steps reported apart as the first ones")->check(CLI::NonNegativeNumber);
    app.add_option("--broadphase", names, "any of smb, dbvt, sap")->delimiter(',');
    app.add_option("--skin", g_skin, "smb's skin")->check(CLI::NonNegativeNumber);
    app.add_option("--scenes", scenes, "any of avalanche, rest, damped (rest damped), asleep (rest asleep)")
        ->delimiter(',')
        ->check(CLI::IsMember({"avalanche", "rest", "damped", "asleep"}));
    CLI11_PARSE(app, argc, argv);

    fmt::print(
        "broadphase,bodies,scene,part,steps,step_ms,broadphase_ms,manifolds,mean_height,awake,asleep,oversized\n");
    const auto wanted = [&scenes](const char* scene) {
        return std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
    };
    for (const std::string& name : names) {
        if (wanted("avalanche")) {
            smb::examples::PileSettings settings;
            settings.bodies = bodies;
            TimedBroadphase timed(make_broadphase(name, bodies));
            smb::examples::PileScene scene(timed, settings);
            Window head;
            Window tail;
            run(scene, timed, motion_steps, first, head, tail);
            print_row(name, bodies, "avalanche", "first", head, scene, timed);
            print_row(name, bodies, "avalanche", "steady", tail, scene, timed);
        }
        if (rest_steps > 0) {
            smb::examples::PileSettings settings;
            settings.bodies = bodies;
            settings.plough = false;
            settings.churn_every = 0;
            if (wanted("rest")) run_rest(name, bodies, "rest", settings, settle_steps, rest_steps);
            // The parked plough left to Bullet's deactivation, and damping and sleeping thresholds
            // as Bullet's ragdoll demo sets them, for Bullet to put the pile's islands to sleep.
            settings.keep_plough_awake = false;
            settings.linear_damping = 0.05f;
            settings.angular_damping = 0.85f;
            settings.linear_sleeping_threshold = 1.6f;
            settings.angular_sleeping_threshold = 2.5f;
            if (wanted("damped")) run_rest(name, bodies, "rest damped", settings, damped_settle_steps, rest_steps);
            settings.spheres = false;
            if (wanted("asleep")) run_rest(name, bodies, "rest asleep", settings, damped_settle_steps, rest_steps);
        }
        std::fflush(stdout);
    }
    return 0;
}
