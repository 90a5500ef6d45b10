// SPDX-License-Identifier: MIT
// The packing fraction of a region, measured as DEM papers do away from walls and the free
// surface: the share of a fine lattice of points that lies inside some sphere. Sampling the
// volume, rather than counting centres, needs no correction for spheres cut by the region's
// faces; with points a tenth of a diameter apart the lattice error is far below the spread
// between packings.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem.hpp"

namespace dem {

double Simulation::packing_fraction(const Vec3& lo, const Vec3& hi, double spacing) const {
    // The spheres that can reach the region, bucketed into cells as wide as the largest sphere.
    const double cell = settings_.diameter;
    const Vec3 from = lo - Vec3{cell, cell, cell};
    std::array<std::size_t, 3> dims{};
    const std::array<double, 3> extent{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
    for (int k = 0; k < 3; ++k) dims[k] = static_cast<std::size_t>(extent[k] / cell) + 3;
    std::vector<std::vector<std::uint32_t>> buckets(dims[0] * dims[1] * dims[2]);
    auto cell_of = [&](const Vec3& p, std::array<std::size_t, 3>& c) {
        const std::array<double, 3> q{(p.x - from.x) / cell, (p.y - from.y) / cell, (p.z - from.z) / cell};
        for (int k = 0; k < 3; ++k) {
            if (q[k] < 0 || q[k] >= static_cast<double>(dims[k])) return false;
            c[k] = static_cast<std::size_t>(q[k]);
        }
        return true;
    };
    for (std::size_t i = 0; i < x_.size(); ++i) {
        std::array<std::size_t, 3> c{};
        if (cell_of(x_[i], c))
            buckets[(c[2] * dims[1] + c[1]) * dims[0] + c[0]].push_back(static_cast<std::uint32_t>(i));
    }
    std::size_t inside = 0;
    std::size_t points = 0;
    for (double z = lo.z + spacing / 2; z < hi.z; z += spacing) {
        for (double y = lo.y + spacing / 2; y < hi.y; y += spacing) {
            for (double x = lo.x + spacing / 2; x < hi.x; x += spacing) {
                const Vec3 p{x, y, z};
                std::array<std::size_t, 3> c{};
                cell_of(p, c);  // inside the grid: the region lies a cell within it
                bool covered = false;
                for (std::size_t dz = c[2] - 1; dz <= c[2] + 1 && !covered; ++dz) {
                    for (std::size_t dy = c[1] - 1; dy <= c[1] + 1 && !covered; ++dy) {
                        for (std::size_t dx = c[0] - 1; dx <= c[0] + 1 && !covered; ++dx) {
                            for (const std::uint32_t i : buckets[(dz * dims[1] + dy) * dims[0] + dx]) {
                                const Vec3 d = p - x_[i];
                                if (dot(d, d) < r_[i] * r_[i]) {
                                    covered = true;
                                    break;
                                }
                            }
                        }
                    }
                }
                inside += covered ? 1 : 0;
                ++points;
            }
        }
    }
    return points == 0 ? 0.0 : static_cast<double>(inside) / static_cast<double>(points);
}

Region interior(const Simulation& simulation, double margin) {
    const Settings& s = simulation.settings();
    std::vector<double> heights;
    for (const Vec3& x : simulation.positions()) heights.push_back(x.z);
    const std::size_t rank = heights.size() * 97 / 100;
    std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(rank), heights.end());
    const double surface = heights.empty() ? 0.0 : heights[rank];
    const double m = margin * s.diameter;
    return Region{Vec3{m, m, m}, Vec3{s.container.x - m, s.container.y - m, std::max(m, surface - m)}};
}

}  // namespace dem
