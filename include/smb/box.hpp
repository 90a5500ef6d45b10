// SPDX-License-Identifier: MIT
#pragma once
// Axis-aligned boxes and the closed overlap convention shared by every part of smb.

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <ranges>

namespace smb {

/// An axis-aligned box in `Dim` dimensions (2 or 3) with coordinates of type `Real`
/// (float or double). A box is valid when every coordinate is finite and
/// min[k] <= max[k] on every axis; zero extent on any axis is allowed.
template <std::floating_point Real, int Dim>
struct Box {
    static_assert(Dim == 2 || Dim == 3, "smb supports 2D and 3D boxes");
    using real_type = Real;
    static constexpr int dimension = Dim;

    std::array<Real, Dim> min{};
    std::array<Real, Dim> max{};

    friend bool operator==(const Box&, const Box&) = default;
};

using Box2f = Box<float, 2>;
using Box2d = Box<double, 2>;
using Box3f = Box<float, 3>;
using Box3d = Box<double, 3>;

namespace detail {
template <class T>
inline constexpr bool is_box = false;
template <std::floating_point Real, int Dim>
inline constexpr bool is_box<Box<Real, Dim>> = true;
}  // namespace detail

/// A contiguous range of boxes of one type: std::vector, std::array, std::span (of const boxes
/// or not), a C array.
template <class Range>
concept BoxRange = std::ranges::contiguous_range<const Range> && std::ranges::sized_range<const Range> &&
    detail::is_box<std::ranges::range_value_t<const Range>>;

/// True when every coordinate is finite and min <= max on every axis.
template <std::floating_point Real, int Dim>
[[nodiscard]] constexpr bool is_valid(const Box<Real, Dim>& box) noexcept {
    for (int k = 0; k < Dim; ++k) {
        if (!std::isfinite(box.min[k]) || !std::isfinite(box.max[k])) return false;
        if (!(box.min[k] <= box.max[k])) return false;
    }
    return true;
}

/// Closed overlap: boxes that only touch (share a face, an edge or a corner) overlap.
/// a and b overlap iff a.min[k] <= b.max[k] and b.min[k] <= a.max[k] on every axis k.
/// -0.0 and +0.0 compare equal, as IEEE 754 says.
template <std::floating_point Real, int Dim>
[[nodiscard]] constexpr bool overlaps(const Box<Real, Dim>& a, const Box<Real, Dim>& b) noexcept {
    for (int k = 0; k < Dim; ++k) {
        if (a.min[k] > b.max[k] || b.min[k] > a.max[k]) return false;
    }
    return true;
}

}  // namespace smb
