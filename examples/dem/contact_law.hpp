// SPDX-License-Identifier: MIT
#pragma once
// The contact law: a normal spring (linear or Hertzian) with a dashpot, and a tangential spring
// with a dashpot capped by Coulomb friction (Cundall and Strack). The same law serves
// sphere-sphere and sphere-wall contacts: a wall is a body of infinite mass.

#include <algorithm>
#include <cmath>

#include "dem.hpp"
#include "vec3.hpp"

namespace dem {

struct ContactLaw {
    NormalModel model = NormalModel::linear;
    double stiffness = 0;         // k_n
    double tangential_ratio = 0;  // k_t / k_n
    double damping_factor = 0;    // beta: the dashpot is 2 beta sqrt(m k), critical at beta = 1
    double friction = 0;

    /// beta for a coefficient of restitution e of the linear spring-dashpot.
    static double damping_for(double restitution) {
        const double log_e = std::log(std::clamp(restitution, 1e-6, 1.0));
        return -log_e / std::sqrt(M_PI * M_PI + log_e * log_e);
    }

    /// Normal stiffness at this overlap (the slope of the Hertzian force grows as its root).
    [[nodiscard]] double normal_stiffness(double overlap) const {
        return model == NormalModel::linear ? stiffness : stiffness * std::sqrt(overlap);
    }

    /// Force on body a of a contact whose normal `n` points from a to b, with `overlap` > 0,
    /// `slip` the velocity of a's contact point relative to b's, `mass` the reduced mass. The
    /// tangential spring is turned into the present tangent plane, stretched by the tangential
    /// slip over `dt`, and cut back where friction caps its force. `tangential` gets the
    /// tangential part of the force (for the torques).
    Vec3 force(const Vec3& n, double overlap, const Vec3& slip, double mass, double dt, Vec3& spring,
               Vec3& tangential) const {
        const double k = normal_stiffness(overlap);
        const double gamma = 2 * damping_factor * std::sqrt(mass * k);
        const double approach = dot(slip, n);
        const double normal = std::max(0.0, k * overlap + gamma * approach);  // no pull
        const Vec3 slide = slip - approach * n;

        // The contact turned: keep the spring's length, in the new tangent plane.
        const double before = norm(spring);
        spring -= dot(spring, n) * n;
        const double after = norm(spring);
        if (after > 0) spring = (before / after) * spring;
        spring += dt * slide;

        const double kt = tangential_ratio * k;
        const double gamma_t = gamma / 2;
        tangential = -(kt * spring) - gamma_t * slide;
        const double limit = friction * normal;
        const double size = norm(tangential);
        if (size > limit) {  // sliding: the spring stretches no further than friction allows
            tangential = (limit / size) * tangential;
            spring = kt > 0 ? -(1 / kt) * (tangential + gamma_t * slide) : Vec3{};
        }
        return tangential - normal * n;
    }

    /// Energy held by the springs of a contact.
    [[nodiscard]] double energy(double overlap, const Vec3& spring) const {
        const double normal = model == NormalModel::linear ? 0.5 * stiffness * overlap * overlap
                                                           : 0.4 * stiffness * overlap * overlap * std::sqrt(overlap);
        return normal + 0.5 * tangential_ratio * normal_stiffness(overlap) * dot(spring, spring);
    }
};

}  // namespace dem
