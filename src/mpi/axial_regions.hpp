// SPDX-License-Identifier: MIT
#pragma once
// The decomposition of space into one region per rank: axial cuts of equal population, the
// first axis into slabs, each slab on the next axis, and so on (smb's own cuts, across ranks).

#include <mpi.h>

#include <array>
#include <concepts>
#include <cstddef>
#include <span>
#include <vector>

#include "smb/box.hpp"

namespace smb::mpi::detail {

/// The point that counts a box in a region's population: its centre, computed so that it stays
/// finite for any finite box.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::array<Real, Dim> centre_of(const Box<Real, Dim>& box) noexcept {
    std::array<Real, Dim> centre{};
    for (int k = 0; k < Dim; ++k) centre[k] = box.min[k] * Real(0.5) + box.max[k] * Real(0.5);
    return centre;
}

/// Factors `ranks` into per-axis region counts whose product is `ranks`, as even as the
/// prime factors allow (the largest factors first, each to the axis with the fewest regions).
template <int Dim>
[[nodiscard]] std::array<int, Dim> regions_per_axis_for(int ranks);

/// Region r is numbered in mixed radix over the axes: r = (s0 * n1 + s1) * n2 + s2, s_k its
/// slab on axis k and n_k the regions per axis. A region is half-open, [lower, upper) on each
/// axis, and the outer faces are infinite, so every point of space lies in exactly one region.
template <std::floating_point Real, int Dim>
class AxialRegions {
public:
    using box_type = Box<Real, Dim>;

    AxialRegions() = default;
    explicit AxialRegions(int ranks);

    [[nodiscard]] bool has_cuts() const noexcept { return has_cuts_; }
    [[nodiscard]] const std::array<int, Dim>& per_axis() const noexcept { return per_axis_; }

    /// Finds the cuts collectively over every rank's boxes: on each axis in turn, a bisection of
    /// each cut plane with MPI_Allreduce of the counts below it. No rank sees another's boxes.
    void recut(MPI_Comm comm, std::span<const box_type> boxes);

    /// The region whose half-open extent holds `point`.
    [[nodiscard]] int region_of(const std::array<Real, Dim>& point) const noexcept;
    /// Appends to `out` every region that the closed box meets: box.max >= lower and
    /// box.min < upper on every axis. This is what makes the lower-corner rule exact: the lower
    /// corner of two overlapping boxes' intersection lies in both, so its region holds both.
    void regions_of(const box_type& box, std::vector<int>& out) const;
    /// Region r's extent (infinite at the outer faces).
    [[nodiscard]] Box<double, Dim> bounds(int region) const;

private:
    /// The cut planes of axis k in group g (the slabs of the axes before): per_axis_[k] - 1 of
    /// them, ascending.
    [[nodiscard]] const Real* cuts_of(int axis, int group) const noexcept {
        return cuts_[axis].data() + static_cast<std::size_t>(group) * static_cast<std::size_t>(per_axis_[axis] - 1);
    }
    void regions_of_from(const box_type& box, int axis, int group, std::vector<int>& out) const;

    std::array<int, Dim> per_axis_{};
    std::array<int, Dim> groups_{};  // groups (slabs of the axes before) on axis k
    std::array<std::vector<Real>, Dim> cuts_{};
    bool has_cuts_ = false;
};

}  // namespace smb::mpi::detail
