// SPDX-License-Identifier: MIT
// smb_dem: pours spheres into a box and lets them settle; writes the energies over time and the
// final packing as CSV, and prints where the time went.

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/os.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "dem.hpp"

namespace {

void write_particles(const dem::Simulation& simulation, const std::string& path) {
    auto out = fmt::output_file(path);
    out.print("id,x,y,z,radius\n");
    const auto& x = simulation.positions();
    for (std::size_t i = 0; i < x.size(); ++i) {
        out.print("{},{:.9g},{:.9g},{:.9g},{:.9g}\n", i, x[i].x, x[i].y, x[i].z, simulation.radii()[i]);
    }
}

}  // namespace

int main(int argc, char** argv) {
    dem::Settings settings;
    std::size_t steps = 20000;
    std::size_t every = 100;
    bool settle = false;
    std::string energy_csv;
    std::string particles_csv;
    std::vector<double> container{settings.container.x, settings.container.y, settings.container.z};

    CLI::App app{"smb_dem: spheres poured into a box, with smb as the broad phase"};
    app.add_option("-n,--particles", settings.particles, "number of spheres")->capture_default_str();
    app.add_option("-s,--steps", steps, "time steps (at most, with --settle)")->capture_default_str();
    app.add_flag("--settle", settle,
                 "stop once the spheres are at rest (kinetic energy below 1e-6 rho g d^4 per sphere)");
    app.add_option("--container", container, "container size X,Y,Z in diameters")->delimiter(',')->expected(3);
    app.add_option("--spacing", settings.spacing, "initial lattice pitch in diameters")->capture_default_str();
    app.add_option("--polydispersity", settings.polydispersity, "diameters uniform in [1 - p, 1]")
        ->capture_default_str();
    app.add_option("--model", settings.model, "normal spring: linear or hertz")
        ->transform(CLI::CheckedTransformer(std::map<std::string, dem::NormalModel>{
            {"linear", dem::NormalModel::linear}, {"hertz", dem::NormalModel::hertz}}));
    app.add_option("--stiffness", settings.stiffness, "normal stiffness k_n")->capture_default_str();
    app.add_option("--restitution", settings.restitution, "normal coefficient of restitution (1: no damping)")
        ->capture_default_str();
    app.add_option("--friction", settings.friction, "Coulomb friction coefficient (0: none)")->capture_default_str();
    app.add_option("--gravity", settings.gravity, "gravity along -z")->capture_default_str();
    app.add_option("--dt", settings.time_step, "time step (0: a twentieth of the collision time)")
        ->capture_default_str();
    app.add_option("--broad-phase", settings.broad_phase, "smb (Detector with skin and events) or grid")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, dem::BroadPhase>{{"smb", dem::BroadPhase::smb}, {"grid", dem::BroadPhase::grid}}));
    app.add_option("--skin", settings.skin, "broad phase skin, in diameters")->capture_default_str();
    app.add_option("-t,--threads", settings.threads, "threads (broad phase and the force and integration loops)")
        ->capture_default_str();
    app.add_option("--seed", settings.seed, "random seed of the initial lattice's jitter and velocities")
        ->capture_default_str();
    app.add_option("--energy-csv", energy_csv, "write step,time,kinetic,rotational,potential,elastic,total,contacts");
    app.add_option("--every", every, "steps between two rows of the energy CSV")->capture_default_str();
    app.add_option("--particles-csv", particles_csv, "write the final spheres: id,x,y,z,radius");
    CLI11_PARSE(app, argc, argv);
    settings.container = dem::Vec3{container[0], container[1], container[2]};

    try {
        dem::Simulation simulation(settings);
        std::FILE* energy_file = nullptr;
        if (!energy_csv.empty()) {
            energy_file = std::fopen(energy_csv.c_str(), "w");
            if (energy_file == nullptr) throw std::runtime_error("cannot write " + energy_csv);
            fmt::print(energy_file, "step,time,kinetic,rotational,potential,elastic,total,contacts\n");
        }
        auto record = [&] {
            if (energy_file == nullptr) return;
            const dem::Energy e = simulation.energy();
            fmt::print(energy_file, "{},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.12g},{}\n", simulation.steps(),
                       static_cast<double>(simulation.steps()) * simulation.time_step(), e.kinetic, e.rotational,
                       e.potential, e.elastic, e.total(), simulation.touching_pairs());
        };
        const double rest = 1e-6 * static_cast<double>(settings.particles) * settings.density * settings.gravity;
        const auto start = std::chrono::steady_clock::now();
        record();
        for (std::size_t step = 1; step <= steps; ++step) {
            simulation.step();
            if (every > 0 && step % every == 0) record();
            if (settle && step % 100 == 0 && simulation.energy().kinetic < rest) break;
        }
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (energy_file != nullptr) std::fclose(energy_file);
        if (!particles_csv.empty()) write_particles(simulation, particles_csv);

        const dem::Timings& t = simulation.timings();
        const double measured = t.broad_phase + t.contacts + t.integration;
        const double per_step = 1e3 / static_cast<double>(std::max<std::size_t>(1, simulation.steps()));
        const dem::Region region = dem::interior(simulation, 3);
        const dem::Energy e = simulation.energy();
        fmt::print("smb_dem: {} spheres, broad phase {}, {} thread(s), {} springs, e {}, mu {}, dt {:.4g}, skin {} d\n",
                   settings.particles, settings.broad_phase == dem::BroadPhase::smb ? "smb" : "grid", settings.threads,
                   settings.model == dem::NormalModel::linear ? "linear" : "Hertzian", settings.restitution,
                   settings.friction, simulation.time_step(), settings.skin);
        fmt::print("  steps          {} (time {:.3f}), {:.2f} s\n", simulation.steps(),
                   static_cast<double>(simulation.steps()) * simulation.time_step(), wall);
        fmt::print(
            "  per step       {:.3f} ms: broad phase {:.3f} ms ({:.1f}%), contacts {:.3f} ms ({:.1f}%), "
            "integration {:.3f} ms ({:.1f}%)\n",
            measured * per_step, t.broad_phase * per_step, 100 * t.broad_phase / measured, t.contacts * per_step,
            100 * t.contacts / measured, t.integration * per_step, 100 * t.integration / measured);
        fmt::print("  broad phase    {:.3f} ms per step, of which pair events {:.3f} ms; rebuilt at {} of {} steps\n",
                   t.broad_phase * per_step, t.pair_events * per_step, t.rebuilds, simulation.steps());
        fmt::print("  contacts       {} pairs of boxes, {} touching\n", simulation.contact_count(),
                   simulation.touching_pairs());
        fmt::print("  energy         kinetic {:.6g}, rotational {:.6g}, potential {:.6g}, elastic {:.6g}\n", e.kinetic,
                   e.rotational, e.potential, e.elastic);
        if (region.hi.z - region.lo.z > 1 && region.hi.x > region.lo.x) {
            fmt::print("  packing        {:.4f} in [{:.1f}, {:.1f}] x [{:.1f}, {:.1f}] x [{:.1f}, {:.1f}]\n",
                       simulation.packing_fraction(region.lo, region.hi, 0.1 * settings.diameter), region.lo.x,
                       region.hi.x, region.lo.y, region.hi.y, region.lo.z, region.hi.z);
        }
    } catch (const std::exception& error) {
        fmt::print(stderr, "smb_dem: {}\n", error.what());
        return 1;
    }
    return 0;
}
