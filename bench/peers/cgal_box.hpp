// SPDX-License-Identifier: MIT
#pragma once
// The box type smb's benchmarks hand to CGAL's box_intersection_d: float coordinates and an
// index of the caller's choosing.

#include <array>
#include <cstddef>

namespace smb::bench {

/// CGAL breaks ties between equal coordinates by box id, so the index must be unique among all
/// the boxes of one call (over both sequences when there are two).
template <int Dim>
struct CgalBox {
    using NT = float;
    using ID = std::size_t;

    std::array<float, Dim> low{};
    std::array<float, Dim> high{};
    std::size_t index = 0;

    static int dimension() { return Dim; }
    [[nodiscard]] float min_coord(int axis) const { return low[static_cast<std::size_t>(axis)]; }
    [[nodiscard]] float max_coord(int axis) const { return high[static_cast<std::size_t>(axis)]; }
    [[nodiscard]] std::size_t id() const { return index; }
};

}  // namespace smb::bench
