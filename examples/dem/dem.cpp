// SPDX-License-Identifier: MIT
#include "dem.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <random>
#include <span>
#include <stdexcept>

#include "contact_law.hpp"

namespace dem {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Uniform in [lo, hi), the same on every standard library (std::uniform_real_distribution is not).
double uniform(std::mt19937_64& random, double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(random() >> 11) * 0x1.0p-53;
}

smb::DetectorSettings detector_settings(const Settings& settings) {
    smb::DetectorSettings detector;
    detector.skin = settings.skin * settings.diameter;
    detector.threads = settings.threads;
    return detector;
}

ContactLaw law_of(const Settings& settings) {
    return ContactLaw{settings.model, settings.stiffness, settings.tangential_ratio,
                      ContactLaw::damping_for(settings.restitution), settings.friction};
}

double component(const Vec3& v, int axis) { return axis == 0 ? v.x : (axis == 1 ? v.y : v.z); }

Vec3 unit(int axis, double sign) {
    Vec3 u;
    (axis == 0 ? u.x : (axis == 1 ? u.y : u.z)) = sign;
    return u;
}

}  // namespace

Simulation::Simulation(const Settings& settings)
    : settings_(settings),
      threads_(std::max(1, static_cast<int>(settings.threads))),
      detector_(detector_settings(settings)),
      events_(static_cast<unsigned>(settings.threads)),
      grid_(settings.skin * settings.diameter) {
    if (settings.particles == 0 || settings.diameter <= 0 || settings.stiffness <= 0 || settings.polydispersity < 0 ||
        settings.polydispersity >= 1) {
        throw std::invalid_argument(
            "dem: particles, diameter and stiffness must be positive, polydispersity in [0, 1)");
    }
    place_particles();
    // The shortest collision: the two lightest spheres, the stiffest spring (Hertzian: at an
    // overlap of 1% of the diameter).
    const double lightest = *std::min_element(m_.begin(), m_.end());
    const ContactLaw law = law_of(settings);
    const double k = law.normal_stiffness(0.01 * settings.diameter);
    const double collision = M_PI * std::sqrt(0.5 * lightest / k);
    dt_ = settings.time_step > 0 ? settings.time_step : collision / 20;
    find_contacts();
    compute_forces();
}

void Simulation::place_particles() {
    const Settings& s = settings_;
    std::mt19937_64 random(s.seed);
    const double pitch = s.spacing * s.diameter;
    const auto per_x = static_cast<std::size_t>(s.container.x / pitch);
    const auto per_y = static_cast<std::size_t>(s.container.y / pitch);
    const std::size_t layer = per_x * per_y;
    const std::size_t layers = layer == 0 ? 0 : (s.particles + layer - 1) / layer;
    if (layer == 0 || static_cast<double>(layers) * pitch > s.container.z) {
        throw std::invalid_argument("dem: the particles do not fit in the container at this spacing");
    }
    const double jitter = 0.25 * (pitch - s.diameter);
    for (std::size_t i = 0; i < s.particles; ++i) {
        const std::size_t ix = i % per_x;
        const std::size_t iy = (i / per_x) % per_y;
        const std::size_t iz = i / layer;
        const double radius = 0.5 * s.diameter * (1 - s.polydispersity * uniform(random, 0, 1));
        x_.push_back(Vec3{(static_cast<double>(ix) + 0.5) * pitch + uniform(random, -jitter, jitter),
                          (static_cast<double>(iy) + 0.5) * pitch + uniform(random, -jitter, jitter),
                          (static_cast<double>(iz) + 0.5) * pitch + uniform(random, -jitter, jitter)});
        const double speed = s.initial_speed;
        v_.push_back(
            Vec3{uniform(random, -speed, speed), uniform(random, -speed, speed), uniform(random, -speed, speed)});
        r_.push_back(radius);
        const double mass = s.density * 4.0 / 3.0 * M_PI * radius * radius * radius;
        m_.push_back(mass);
        inertia_.push_back(0.4 * mass * radius * radius);
    }
    w_.assign(s.particles, Vec3{});
    f_.assign(s.particles, Vec3{});
    t_.assign(s.particles, Vec3{});
    wall_spring_.assign(s.particles, {});
    boxes_.resize(s.particles);
}

void Simulation::step() {
    auto start = std::chrono::steady_clock::now();
    kick(0.5 * dt_);
    const auto n = static_cast<std::ptrdiff_t>(x_.size());
    const double dt = dt_;
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) x_[i] += dt * v_[i];
    timings_.integration += seconds_since(start);

    find_contacts();
    compute_forces();

    start = std::chrono::steady_clock::now();
    kick(0.5 * dt_);
    timings_.integration += seconds_since(start);
    ++steps_;
}

void Simulation::kick(double half_dt) {
    const auto n = static_cast<std::ptrdiff_t>(x_.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        v_[i] += (half_dt / m_[i]) * f_[i];
        w_[i] += (half_dt / inertia_[i]) * t_[i];
    }
}

void Simulation::find_contacts() {
    const auto start = std::chrono::steady_clock::now();
    const auto n = static_cast<std::ptrdiff_t>(x_.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const Vec3 c = x_[i];
        const double r = r_[i];
        boxes_[i] = smb::Box3d{{c.x - r, c.y - r, c.z - r}, {c.x + r, c.y + r, c.z + r}};
    }
    if (settings_.broad_phase == BroadPhase::smb) {
        // The pairs of boxes that overlap, and those that began and ended since the last step
        // (each sorted by (a, b)): all the contact list needs to keep its history. One call,
        // detector_.detect(boxes_, pairs_, events_), does both; two calls time them apart.
        const smb::DetectStats stats = detector_.detect(boxes_, pairs_);
        timings_.rebuilds += stats.skin_rebuilt ? 1 : 0;
        const auto events = std::chrono::steady_clock::now();
        events_.update(pairs_);
        timings_.pair_events += seconds_since(events);
        timings_.broad_phase += seconds_since(start);
        const auto merge = std::chrono::steady_clock::now();
        contacts_.apply_events(events_.ended(), events_.begun());
        timings_.contacts += seconds_since(merge);
    } else {
        const std::size_t rebuilds = grid_.rebuilds();
        grid_.detect(boxes_, pairs_);  // sorted by (a, b)
        timings_.rebuilds += grid_.rebuilds() - rebuilds;
        timings_.broad_phase += seconds_since(start);
        const auto merge = std::chrono::steady_clock::now();
        contacts_.assign_sorted(pairs_);
        timings_.contacts += seconds_since(merge);
    }
}

void Simulation::compute_forces() {
    const auto start = std::chrono::steady_clock::now();
    const ContactLaw law = law_of(settings_);
    const double dt = dt_;
    const double g = settings_.gravity;
    const Vec3 container = settings_.container;
    const auto n = static_cast<std::ptrdiff_t>(x_.size());
    // Gravity and the walls: each sphere on its own.
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        Vec3 force{0, 0, -m_[i] * g};
        Vec3 torque;
        for (int wall = 0; wall < 6; ++wall) {
            const int axis = wall / 2;
            const bool upper = wall % 2 == 1;
            const double gap = upper ? component(container, axis) - component(x_[i], axis) : component(x_[i], axis);
            Vec3& spring = wall_spring_[i][wall];
            const double overlap = r_[i] - gap;
            if (overlap <= 0) {
                spring = Vec3{};
                continue;
            }
            const Vec3 normal = unit(axis, upper ? 1 : -1);  // from the sphere into the wall
            const Vec3 slip = v_[i] + r_[i] * cross(w_[i], normal);
            Vec3 tangential;
            force += law.force(normal, overlap, slip, m_[i], dt, spring, tangential);
            torque += r_[i] * cross(normal, tangential);
        }
        f_[i] = force;
        t_[i] = torque;
    }
    // Sphere pairs: each contact's push is computed apart, then summed in the list's order, so
    // that the sums, and the trajectories, are the same bits whatever the number of threads.
    const std::span<Contact> contacts = contacts_.contacts();
    pushes_.resize(contacts.size());
    const auto count = static_cast<std::ptrdiff_t>(contacts.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::ptrdiff_t c = 0; c < count; ++c) {
        Contact& contact = contacts[c];
        const std::uint32_t a = contact.a;
        const std::uint32_t b = contact.b;
        const Vec3 d = x_[b] - x_[a];
        const double distance = norm(d);
        const double overlap = r_[a] + r_[b] - distance;
        if (overlap <= 0 || distance == 0) {  // boxes overlap, spheres do not: no force, no history
            contact.spring = Vec3{};
            pushes_[c] = Push{};
            continue;
        }
        const Vec3 normal = (1 / distance) * d;
        const Vec3 slip = v_[a] - v_[b] + cross(r_[a] * w_[a] + r_[b] * w_[b], normal);
        const double mass = m_[a] * m_[b] / (m_[a] + m_[b]);
        Vec3 tangential;
        const Vec3 force = law.force(normal, overlap, slip, mass, dt, contact.spring, tangential);
        pushes_[c] = Push{force, r_[a] * cross(normal, tangential), r_[b] * cross(normal, tangential)};
    }
    for (std::size_t c = 0; c < contacts.size(); ++c) {
        const Push& push = pushes_[c];
        f_[contacts[c].a] += push.force;
        f_[contacts[c].b] -= push.force;
        t_[contacts[c].a] += push.torque_a;
        t_[contacts[c].b] += push.torque_b;
    }
    timings_.contacts += seconds_since(start);
}

Energy Simulation::energy() const {
    const ContactLaw law = law_of(settings_);
    Energy e;
    for (std::size_t i = 0; i < x_.size(); ++i) {
        e.kinetic += 0.5 * m_[i] * dot(v_[i], v_[i]);
        e.rotational += 0.5 * inertia_[i] * dot(w_[i], w_[i]);
        e.potential += m_[i] * settings_.gravity * x_[i].z;
        for (int wall = 0; wall < 6; ++wall) {
            const int axis = wall / 2;
            const double gap =
                wall % 2 == 1 ? component(settings_.container, axis) - component(x_[i], axis) : component(x_[i], axis);
            if (r_[i] > gap) e.elastic += law.energy(r_[i] - gap, wall_spring_[i][wall]);
        }
    }
    for (const Contact& contact : contacts_.contacts()) {
        const double overlap = r_[contact.a] + r_[contact.b] - norm(x_[contact.b] - x_[contact.a]);
        if (overlap > 0) e.elastic += law.energy(overlap, contact.spring);
    }
    return e;
}

std::size_t Simulation::touching_pairs() const {
    std::size_t touching = 0;
    for (const Contact& contact : contacts_.contacts()) {
        touching += r_[contact.a] + r_[contact.b] > norm(x_[contact.b] - x_[contact.a]) ? 1 : 0;
    }
    return touching;
}

double Simulation::top() const {
    double top = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) top = std::max(top, x_[i].z + r_[i]);
    return top;
}

}  // namespace dem
