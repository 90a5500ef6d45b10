// SPDX-License-Identifier: MIT
#pragma once
// The ray walk of smb::BoxIndex: on each level, the cells a ray crosses, slab by slab along its
// dominant axis, and the home cells of the boxes that reach into them (a box's home cell is that
// of its lower corner: down to the level's reach below the cells crossed). A box is tested in
// the slab where the ray enters it, or earlier. Every cell is found with a margin (a millionth of a cell, more far from the
// grid's origin, where rounding is coarser), so that a box the exact test (smb::ray_entry)
// accepts is always a candidate, even for rays along cell boundaries or box faces.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "query/grid_index.hpp"
#include "smb/query.hpp"

namespace smb::detail {

/// A candidate hit: a position in GridIndex::boxes and its entry parameter (rounded to Real).
struct RayCandidate {
    double t = 0;
    BoxId id = 0;
    std::uint32_t position = 0;

    friend bool operator<(const RayCandidate& a, const RayCandidate& b) noexcept {
        if (a.t != b.t) return a.t < b.t;
        if (a.id != b.id) return a.id < b.id;
        return a.position < b.position;
    }
};

/// Walks `ray` (valid) through every level of `grid`. For each box it enters, calls
/// hit(RayCandidate) (a box may be reported more than once, from several cells). With `nearest`,
/// stops a level's walk once the cells ahead start beyond best().t, where best() is the best
/// hit so far (or nullptr).
template <std::floating_point Real, int Dim, class Hit, class Best>
void walk_ray(const GridIndex<Real, Dim>& grid, const Ray<Real, Dim>& ray, bool nearest, Hit&& hit, Best&& best) {
    if (grid.boxes.empty()) return;
    const double max_t = static_cast<double>(ray.max_t);
    auto test_cells = [&](std::size_t first_cell, std::size_t last_cell) {
        for (std::uint32_t p = grid.cell_start[first_cell]; p < grid.cell_start[last_cell + 1]; ++p) {
            // The order of hits is that of the reported t, rounded to Real, so that (t, id) order
            // holds for what the caller sees.
            if (const auto t = ray_entry(ray, grid.boxes[p]))
                hit(RayCandidate{static_cast<double>(static_cast<Real>(*t)), grid.ids[p], p});
        }
    };
    auto beyond_best = [&](double t) {
        const RayCandidate* b = best();
        // Beyond every t that rounds to the best's: a box entered there cannot tie with it.
        return nearest && b != nullptr &&
               t > static_cast<double>(std::nextafter(static_cast<Real>(b->t), std::numeric_limits<Real>::infinity()));
    };

    for (const GridLevel<Dim>& level : grid.levels) {
        std::int64_t cells = 1;
        for (int k = 0; k < Dim; ++k) cells *= level.n[k];
        if (cells == 1) {  // nothing to walk (and no geometry where the scene's extent overflows)
            test_cells(level.first_cell, level.first_cell);
            continue;
        }
        // The ray in this level's grid coordinates, where cell c spans [c, c + 1) on each axis.
        std::array<double, Dim> go{};
        std::array<double, Dim> gd{};
        double magnitude = 0;
        std::int64_t cells_across = 1;
        int a = 0;
        for (int k = 0; k < Dim; ++k) {
            go[k] = (static_cast<double>(ray.origin[k]) - grid.origin[k]) * level.inv;
            gd[k] = static_cast<double>(ray.direction[k]) * level.inv;
            magnitude = std::max(magnitude, std::abs(go[k]));
            cells_across = std::max(cells_across, level.n[k]);
            if (std::abs(gd[k]) > std::abs(gd[a])) a = k;
        }
        bool finite = std::isfinite(magnitude);
        for (int k = 0; k < Dim; ++k) finite = finite && std::isfinite(gd[k]);
        if (!finite) {  // a ray from near one end of double's range to a scene near the other
            test_cells(level.first_cell, level.first_cell + static_cast<std::size_t>(cells) - 1);
            continue;
        }
        // The level's reach in cells: a box reaches at most this far above its home cell.
        std::array<double, Dim> reach{};
        for (int k = 0; k < Dim; ++k) reach[k] = level.reach[k] * level.inv;
        // The margin, in cells: far more than the rounding of the grid coordinates and of the
        // exact test, both relative to the coordinates' magnitude.
        const double w = 1e-6 + 1e-12 * (magnitude + static_cast<double>(cells_across));

        if (gd[a] == 0) {  // the zero-length segment: the cells around its point
            std::array<std::int64_t, Dim> lo{};
            std::array<std::int64_t, Dim> hi{};
            bool inside = true;
            for (int k = 0; k < Dim; ++k) {
                inside = inside && go[k] + w >= 0 && go[k] - w <= static_cast<double>(level.n[k]);
                lo[k] = clamped_cell(go[k] - w - reach[k], level.n[k]);
                hi[k] = clamped_cell(go[k] + w, level.n[k]);
            }
            if (inside) GridIndex<Real, Dim>::for_rows(lo, hi, level, test_cells);
            continue;
        }

        // Clip to the grid widened by the margin: [t0, t1].
        double t0 = 0;
        double t1 = max_t;
        bool inside = true;
        for (int k = 0; k < Dim && inside; ++k) {
            const double lo = -w;
            const double hi = static_cast<double>(level.n[k]) + w;
            if (gd[k] == 0) {
                inside = go[k] >= lo && go[k] <= hi;
                continue;
            }
            double ta = (lo - go[k]) / gd[k];
            double tb = (hi - go[k]) / gd[k];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
            inside = t0 <= t1;
        }
        if (!inside) continue;

        // Slabs of the dominant axis, in the order the ray meets them.
        const double ga0 = go[a] + t0 * gd[a];
        const double ga1 = go[a] + t1 * gd[a];
        const std::int64_t s_first = clamped_cell((gd[a] > 0 ? ga0 - w : ga0 + w), level.n[a]);
        const std::int64_t s_last = clamped_cell((gd[a] > 0 ? ga1 + w : ga1 - w), level.n[a]);
        const std::int64_t step = gd[a] > 0 ? 1 : -1;
        for (std::int64_t s = s_first;; s += step) {
            // The piece of the ray in slab s widened by the margin, as a t interval in [t0, t1].
            double ta = (static_cast<double>(s) - w - go[a]) / gd[a];
            double tb = (static_cast<double>(s + 1) + w - go[a]) / gd[a];
            if (ta > tb) std::swap(ta, tb);
            ta = std::clamp(ta, t0, t1);
            tb = std::clamp(tb, t0, t1);
            if (beyond_best(ta)) break;
            std::array<std::int64_t, Dim> lo{};
            std::array<std::int64_t, Dim> hi{};
            lo[a] = clamped_cell(static_cast<double>(s) - w - reach[a], level.n[a]);
            hi[a] = s;
            for (int k = 0; k < Dim; ++k) {
                if (k == a) continue;
                const double pa = go[k] + ta * gd[k];
                const double pb = go[k] + tb * gd[k];
                lo[k] = clamped_cell(std::min(pa, pb) - w - reach[k], level.n[k]);
                hi[k] = clamped_cell(std::max(pa, pb) + w, level.n[k]);
            }
            GridIndex<Real, Dim>::for_rows(lo, hi, level, test_cells);
            if (s == s_last) break;
        }
    }
}

/// The hits of a walk, as a cast reports them: the nearest, or all sorted by (t, id), each once.
template <std::floating_point Real, int Dim>
void cast_ray(const GridIndex<Real, Dim>& grid, const Ray<Real, Dim>& ray, RayHits mode,
              std::vector<RayHit<Real>>& out) {
    if (mode == RayHits::nearest) {
        RayCandidate best;
        bool found = false;
        walk_ray(
            grid, ray, true,
            [&](const RayCandidate& c) {
                if (!found || c < best) best = c;
                found = true;
            },
            [&]() -> const RayCandidate* { return found ? &best : nullptr; });
        out.clear();
        if (found) out.push_back(RayHit<Real>{best.id, static_cast<Real>(best.t)});
        return;
    }
    std::vector<RayCandidate> scratch;
    walk_ray(
        grid, ray, false, [&](const RayCandidate& c) { scratch.push_back(c); },
        []() -> const RayCandidate* { return nullptr; });
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end(),
                              [](const RayCandidate& x, const RayCandidate& y) { return x.position == y.position; }),
                  scratch.end());
    out.clear();
    out.reserve(scratch.size());
    for (const RayCandidate& c : scratch) out.push_back(RayHit<Real>{c.id, static_cast<Real>(c.t)});
}

}  // namespace smb::detail
