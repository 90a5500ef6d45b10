// SPDX-License-Identifier: MIT
#pragma once
// What region queries and ray casts take and return (smb::BoxIndex, World::query, World::cast_ray),
// and the ray-box test that defines a ray hit.

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>

#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb {

/// One answer of a batch of box queries: the box `id` overlaps the query box at index `query`.
struct QueryHit {
    std::size_t query = 0;
    BoxId id = 0;

    friend auto operator<=>(const QueryHit&, const QueryHit&) = default;
};

/// A ray or a segment: the points origin + t * direction for t in [0, max_t]. The direction
/// need not be normalised; t is measured in units of it (with a unit direction, t is the
/// distance). max_t = +infinity (the default) is the whole ray.
///
/// Valid when origin and direction are finite and max_t is >= 0 (not NaN; +infinity allowed). A
/// zero direction is valid only with a finite max_t: it is the zero-length segment, the point
/// `origin`, which enters (t = 0) every box containing it. A zero direction with an infinite
/// max_t has no meaning and is refused.
template <std::floating_point Real, int Dim>
struct Ray {
    static_assert(Dim == 2 || Dim == 3, "smb supports 2D and 3D rays");
    using real_type = Real;
    static constexpr int dimension = Dim;

    std::array<Real, Dim> origin{};
    std::array<Real, Dim> direction{};
    Real max_t = std::numeric_limits<Real>::infinity();

    /// The segment from `from` to `to`: direction = to - from, max_t = 1, so t is the fraction of
    /// the way. from == to gives the zero-length segment. (to - from overflowing to infinity makes
    /// an invalid ray.)
    [[nodiscard]] static constexpr Ray segment(const std::array<Real, Dim>& from, const std::array<Real, Dim>& to) {
        Ray ray;
        ray.origin = from;
        for (int k = 0; k < Dim; ++k) ray.direction[k] = to[k] - from[k];
        ray.max_t = Real(1);
        return ray;
    }

    friend bool operator==(const Ray&, const Ray&) = default;
};

using Ray2f = Ray<float, 2>;
using Ray2d = Ray<double, 2>;
using Ray3f = Ray<float, 3>;
using Ray3d = Ray<double, 3>;

/// Which boxes a cast reports.
enum class RayHits {
    nearest,  ///< the box entered first: least t, then least id; nothing if no box is entered
    all,      ///< every box entered, sorted by (t, id)
};

/// A box the ray enters, at origin + t * direction; t = 0 when the origin is inside the box.
/// t is computed in double (smb::ray_entry) and rounded to Real; the (t, id) order of the hits
/// is that of this rounded t.
template <std::floating_point Real>
struct RayHit {
    BoxId id = 0;
    Real t = 0;

    friend bool operator==(const RayHit&, const RayHit&) = default;
};

/// True when every coordinate is finite, max_t >= 0, and the direction is nonzero or max_t finite.
template <std::floating_point Real, int Dim>
[[nodiscard]] bool is_valid(const Ray<Real, Dim>& ray) noexcept {
    bool moving = false;
    for (int k = 0; k < Dim; ++k) {
        if (!std::isfinite(ray.origin[k]) || !std::isfinite(ray.direction[k])) return false;
        moving = moving || ray.direction[k] != 0;
    }
    if (std::isnan(ray.max_t) || ray.max_t < 0) return false;
    return moving || std::isfinite(ray.max_t);
}

/// The entry parameter of a valid ray into a box (closed: grazing a face, an edge or a corner
/// counts), or nothing when it misses it within [0, max_t]. This slab test, computed in double,
/// is the definition of a hit every cast uses: BoxIndex reports exactly the boxes for which it
/// gives a value, with that value.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::optional<double> ray_entry(const Ray<Real, Dim>& ray, const Box<Real, Dim>& box) noexcept {
    double enter = 0;
    double leave = static_cast<double>(ray.max_t);
    for (int k = 0; k < Dim; ++k) {
        const double o = ray.origin[k];
        const double d = ray.direction[k];
        const double lo = box.min[k];
        const double hi = box.max[k];
        if (d == 0) {
            if (o < lo || o > hi) return std::nullopt;
            continue;
        }
        double a = (lo - o) / d;
        double b = (hi - o) / d;
        if (a > b) std::swap(a, b);
        enter = std::max(enter, a);
        leave = std::min(leave, b);
        if (enter > leave) return std::nullopt;
    }
    return enter;
}

}  // namespace smb
