// SPDX-License-Identifier: MIT
// A Bullet rigid-body pile on smb's broad phase. The switch is the one line that makes the broad
// phase: `smb::bullet::Broadphase broadphase;` in place of `btDbvtBroadphase broadphase;`; the
// rest of the program is Bullet as usual. --broadphase picks Bullet's own to compare.
//
//   smb_bullet_pile --bodies 5000 --steps 600 --broadphase smb

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <chrono>
#include <memory>
#include <string>

#include "pile_scene.hpp"
#include "smb/bullet/broadphase.hpp"

namespace {

std::unique_ptr<btBroadphaseInterface> make_broadphase(const std::string& name) {
    if (name == "smb") return std::make_unique<smb::bullet::Broadphase>();
    if (name == "dbvt") return std::make_unique<btDbvtBroadphase>();
    // btAxisSweep3 needs the world's bounds up front; smb and btDbvtBroadphase do not.
    return std::make_unique<bt32BitAxisSweep3>(btVector3(-1000, -100, -1000), btVector3(1000, 1000, 1000));
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"A Bullet pile of boxes and spheres with a kinematic plough, on smb's broad phase"};
    app.option_defaults()->always_capture_default();  // --help shows each option's default
    smb::examples::PileSettings settings;
    int steps = 600;
    int report_every = 100;
    std::string broadphase_name = "smb";
    app.add_option("--bodies", settings.bodies, "boxes and spheres poured")->check(CLI::Range(1, 10'000'000));
    app.add_option("--steps", steps, "steps of 1/60 s")->check(CLI::NonNegativeNumber);
    app.add_option("--report-every", report_every, "steps between lines of output")->check(CLI::PositiveNumber);
    app.add_option("--broadphase", broadphase_name, "smb, dbvt or sap")->check(CLI::IsMember({"smb", "dbvt", "sap"}));
    app.add_option("--seed", settings.seed, "of the pour's jitter and the bodies taken out");
    CLI11_PARSE(app, argc, argv);

    const std::unique_ptr<btBroadphaseInterface> broadphase = make_broadphase(broadphase_name);
    smb::examples::PileScene scene(*broadphase, settings);
    fmt::print("step,mean_height,contacts,manifolds,kinetic_energy,step_ms\n");
    double window_ms = 0;
    for (int step = 1; step <= steps; ++step) {
        const auto start = std::chrono::steady_clock::now();
        scene.step();
        window_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (step % report_every == 0 || step == steps) {
            const smb::examples::PileMeasure measure = scene.measure();
            const int window = step % report_every == 0 ? report_every : step % report_every;
            fmt::print("{},{:.4f},{},{},{:.3f},{:.3f}\n", step, measure.mean_height, measure.contacts,
                       measure.manifolds, measure.kinetic_energy, window_ms / window);
            window_ms = 0;
        }
    }
    return 0;
}
