// SPDX-License-Identifier: MIT
#include "grid_broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

namespace {

bool inside(const smb::Box3d& box, const smb::Box3d& fat) {
    bool in = true;
    for (int k = 0; k < 3; ++k) in &= fat.min[k] <= box.min[k] && box.max[k] <= fat.max[k];
    return in;
}

}  // namespace

void GridBroadPhase::detect(std::span<const smb::Box3d> boxes, std::vector<smb::Pair>& pairs) {
    bool contained = fat_.size() == boxes.size();
    for (std::size_t i = 0; contained && i < boxes.size(); ++i) contained = inside(boxes[i], fat_[i]);
    if (!contained) rebuild(boxes);
    pairs.clear();
    for (const smb::Pair& candidate : candidates_) {
        if (smb::overlaps(boxes[candidate.a], boxes[candidate.b])) pairs.push_back(candidate);
    }
}

void GridBroadPhase::rebuild(std::span<const smb::Box3d> boxes) {
    ++rebuilds_;
    fat_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            fat_[i].min[k] = boxes[i].min[k] - skin_;
            fat_[i].max[k] = boxes[i].max[k] + skin_;
        }
    }
    candidates_.clear();
    if (boxes.empty()) return;
    sort_into_cells(boxes);
    // Half stencil: the cell itself, and the 13 neighbours that come after it in (z, y, x) order.
    static constexpr std::array<std::array<int, 3>, 13> kForward{{{1, 0, 0},
                                                                  {-1, 1, 0},
                                                                  {0, 1, 0},
                                                                  {1, 1, 0},
                                                                  {-1, -1, 1},
                                                                  {0, -1, 1},
                                                                  {1, -1, 1},
                                                                  {-1, 0, 1},
                                                                  {0, 0, 1},
                                                                  {1, 0, 1},
                                                                  {-1, 1, 1},
                                                                  {0, 1, 1},
                                                                  {1, 1, 1}}};
    const auto [nx, ny, nz] = dims_;
    for (std::size_t z = 0; z < nz; ++z) {
        for (std::size_t y = 0; y < ny; ++y) {
            for (std::size_t x = 0; x < nx; ++x) {
                const std::size_t cell = (z * ny + y) * nx + x;
                if (cell_start_[cell] == cell_start_[cell + 1]) continue;
                pair_cells(cell, cell);
                for (const auto& [dx, dy, dz] : kForward) {
                    const std::size_t ox = x + static_cast<std::size_t>(dx);  // wraps below 0: > nx
                    const std::size_t oy = y + static_cast<std::size_t>(dy);
                    const std::size_t oz = z + static_cast<std::size_t>(dz);
                    if (ox >= nx || oy >= ny || oz >= nz) continue;
                    pair_cells(cell, (oz * ny + oy) * nx + ox);
                }
            }
        }
    }
    std::sort(candidates_.begin(), candidates_.end());
}

void GridBroadPhase::sort_into_cells(std::span<const smb::Box3d> boxes) {
    // Cells as wide as the widest fat box, over the fat boxes' bounds; if the scene is sparse,
    // wider cells, so that there are at most about two cells per box.
    std::array<double, 3> hi{};
    double widest = 0;
    for (int k = 0; k < 3; ++k) {
        lo_[k] = fat_[0].min[k];
        hi[k] = fat_[0].max[k];
    }
    for (const smb::Box3d& fat : fat_) {
        for (int k = 0; k < 3; ++k) {
            lo_[k] = std::min(lo_[k], fat.min[k]);
            hi[k] = std::max(hi[k], fat.max[k]);
            widest = std::max(widest, fat.max[k] - fat.min[k]);
        }
    }
    // The margin keeps two centres one cell apart from landing two cells apart by rounding.
    double cell = std::max(widest * (1 + 1e-9), 1e-300);
    const double volume = (hi[0] - lo_[0]) * (hi[1] - lo_[1]) * (hi[2] - lo_[2]);
    cell = std::max(cell, std::cbrt(volume / (2.0 * static_cast<double>(boxes.size()))));
    inverse_cell_ = 1 / cell;
    std::size_t cells = 1;
    for (int k = 0; k < 3; ++k) {
        dims_[k] = static_cast<std::size_t>((hi[k] - lo_[k]) * inverse_cell_) + 1;
        cells *= dims_[k];
    }
    // Counting sort of the boxes by the cell of their centre.
    cell_of_.resize(boxes.size());
    cell_start_.assign(cells + 1, 0);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        std::array<std::size_t, 3> c{};
        for (int k = 0; k < 3; ++k) {
            const double centre = 0.5 * (fat_[i].min[k] + fat_[i].max[k]);
            c[k] = std::min(static_cast<std::size_t>((centre - lo_[k]) * inverse_cell_), dims_[k] - 1);
        }
        cell_of_[i] = static_cast<std::uint32_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
        ++cell_start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
    order_.resize(boxes.size());
    sorted_fat_.resize(boxes.size());
    std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const std::uint32_t slot = next[cell_of_[i]]++;
        order_[slot] = static_cast<std::uint32_t>(i);
        sorted_fat_[slot] = fat_[i];
    }
}

void GridBroadPhase::pair_cells(std::size_t cell, std::size_t other) {
    const std::uint32_t first = cell_start_[cell];
    const std::uint32_t last = cell_start_[cell + 1];
    const std::uint32_t other_last = cell_start_[other + 1];
    for (std::uint32_t p = first; p < last; ++p) {
        const smb::Box3d& box = sorted_fat_[p];
        // In its own cell a box meets only those after it: each pair once.
        for (std::uint32_t q = cell == other ? p + 1 : cell_start_[other]; q < other_last; ++q) {
            if (!smb::overlaps(box, sorted_fat_[q])) continue;
            const std::uint32_t a = order_[p];
            const std::uint32_t b = order_[q];
            candidates_.push_back(a < b ? smb::Pair{a, b} : smb::Pair{b, a});
        }
    }
}

}  // namespace dem
