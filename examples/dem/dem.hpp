// SPDX-License-Identifier: MIT
#pragma once
// A small discrete-element simulation: spheres poured into a box-shaped container under
// gravity, with spring-dashpot contacts, Coulomb friction and velocity Verlet. smb's Detector
// (with a skin) is the broad phase; its events keep the tangential springs' history.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contact_list.hpp"
#include "grid_broad_phase.hpp"
#include "smb/detector.hpp"
#include "smb/pair_events.hpp"
#include "vec3.hpp"

namespace dem {

enum class NormalModel {
    linear,  // force k_n * overlap
    hertz,   // force k_n * overlap^(3/2)
};

enum class BroadPhase { smb, grid };

/// Everything a run depends on, in units where the largest diameter, the density and the
/// gravity are 1 (time in units of sqrt(d / g)).
struct Settings {
    std::size_t particles = 2000;
    double diameter = 1;        // the largest
    double polydispersity = 0;  // diameters uniform in [diameter * (1 - p), diameter]
    double density = 1;
    double gravity = 1;          // along -z
    Vec3 container{12, 12, 60};  // walls at 0 and at these coordinates
    double spacing = 1.25;       // of the initial lattice, in diameters
    double initial_speed = 0.1;  // random initial velocities up to this, on each axis

    NormalModel model = NormalModel::linear;
    double stiffness = 2000;            // k_n (linear: force per length; Hertz: per length^1.5)
    double tangential_ratio = 2.0 / 7;  // k_t / k_n
    double restitution = 0.5;           // normal coefficient of restitution: sets the damping
    double friction = 0.5;              // Coulomb coefficient, particles and walls
    double time_step = 0;               // 0: a twentieth of the collision time

    BroadPhase broad_phase = BroadPhase::smb;
    double skin = 0.1;  // the broad phase's fat boxes stick out by this on every side, in diameters
    std::size_t threads = 1;
    std::uint64_t seed = 1;
};

/// Energies of the system now. With restitution 1 and no friction, total() is conserved up to
/// the integrator's error.
struct Energy {
    double kinetic = 0;     // translation
    double rotational = 0;  // spin
    double potential = 0;   // gravity, from z = 0
    double elastic = 0;     // normal and tangential springs, particles and walls
    [[nodiscard]] double total() const { return kinetic + rotational + potential + elastic; }
};

/// Seconds spent in each part of the steps so far.
struct Timings {
    double broad_phase = 0;    // boxes, detection and events, or the grid
    double pair_events = 0;    // of broad_phase: smb's events (the grid's pairs come sorted)
    std::size_t rebuilds = 0;  // steps whose broad phase rebuilt its candidates from scratch
    double contacts = 0;       // contact list, contact and wall forces
    double integration = 0;    // the two half kicks and the drift
};

class Simulation {
public:
    explicit Simulation(const Settings& settings);

    /// One velocity Verlet step: half kick, drift, forces at the new positions, half kick.
    void step();

    [[nodiscard]] Energy energy() const;
    /// Volume fraction of the spheres inside the region [lo, hi], sampled on a lattice of
    /// points `spacing` apart.
    [[nodiscard]] double packing_fraction(const Vec3& lo, const Vec3& hi, double spacing) const;
    /// Pairs of spheres that touch now.
    [[nodiscard]] std::size_t touching_pairs() const;
    /// Highest top of a sphere.
    [[nodiscard]] double top() const;

    [[nodiscard]] const Settings& settings() const noexcept { return settings_; }
    [[nodiscard]] double time_step() const noexcept { return dt_; }
    [[nodiscard]] std::size_t steps() const noexcept { return steps_; }
    [[nodiscard]] const std::vector<Vec3>& positions() const noexcept { return x_; }
    [[nodiscard]] const std::vector<Vec3>& velocities() const noexcept { return v_; }
    [[nodiscard]] const std::vector<Vec3>& spins() const noexcept { return w_; }
    [[nodiscard]] const std::vector<double>& radii() const noexcept { return r_; }
    [[nodiscard]] const Timings& timings() const noexcept { return timings_; }
    [[nodiscard]] std::size_t contact_count() const noexcept { return contacts_.contacts().size(); }

private:
    void place_particles();
    void find_contacts();
    void compute_forces();
    void kick(double half_dt);

    Settings settings_;
    double dt_ = 0;
    std::size_t steps_ = 0;
    int threads_ = 1;

    // Per particle.
    std::vector<Vec3> x_, v_, w_;  // position, velocity, angular velocity
    std::vector<Vec3> f_, t_;      // force, torque
    std::vector<double> r_, m_, inertia_;
    std::vector<std::array<Vec3, 6>> wall_spring_;  // tangential springs against the six walls

    // Broad phase.
    std::vector<smb::Box3d> boxes_;
    smb::Detector3d detector_;
    smb::PairEvents events_;
    GridBroadPhase grid_;
    std::vector<smb::Pair> pairs_;
    ContactList contacts_;

    /// What one contact gives, computed in parallel and summed in list order.
    struct Push {
        Vec3 force;  // on a; b gets the opposite
        Vec3 torque_a, torque_b;
    };
    std::vector<Push> pushes_;
    Timings timings_;
};

/// A region of the packing away from its boundaries: `margin` diameters inside the side walls
/// and the floor, and below the free surface (the height under which 97% of the centres lie).
struct Region {
    Vec3 lo, hi;
};
[[nodiscard]] Region interior(const Simulation& simulation, double margin);

}  // namespace dem
