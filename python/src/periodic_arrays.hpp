// SPDX-License-Identifier: MIT
#pragma once
// Periodic domains from Python arguments, and periodic pairs back as two arrays.

#include <pybind11/numpy.h>

#include <cstdint>
#include <vector>

#include "arrays.hpp"
#include "smb/periodic.hpp"

namespace smb::python {

/// The domain wrapping each axis k with axes[k] set (every axis when `axes` is None) over
/// [lo[k], hi[k]). The library checks the bounds themselves (ArgumentError).
template <std::floating_point Real, int Dim>
PeriodicDomain<Real, Dim> periodic_domain(py::handle lo, py::handle hi, py::handle axes) {
    PeriodicDomain<Real, Dim> domain;
    domain.lo = coordinates<Real, Dim>(lo, "lo");
    domain.hi = coordinates<Real, Dim>(hi, "hi");
    const std::vector<std::uint8_t> wrapped =
        axes.is_none() ? std::vector<std::uint8_t>(Dim, 1) : flag_values(axes, Dim, "axes", "axis");
    for (int k = 0; k < Dim; ++k)
        domain.periodic[static_cast<std::size_t>(k)] = wrapped[static_cast<std::size_t>(k)] != 0;
    return domain;
}

/// (pairs, shifts): a (P, 2) array of the pairs (dtype Id) and a (P, Dim) int32 array of
/// their shifts, in periods.
template <int Dim, OutputId Id>
py::tuple periodic_result(const std::vector<PeriodicPair>& pairs) {
    const auto count = static_cast<py::ssize_t>(pairs.size());
    py::array_t<Id> ends({count, py::ssize_t{2}});
    py::array_t<std::int32_t> shifts({count, py::ssize_t{Dim}});
    auto end_view = ends.template mutable_unchecked<2>();
    auto shift_view = shifts.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < count; ++i) {
        const PeriodicPair& pair = pairs[static_cast<std::size_t>(i)];
        end_view(i, 0) = static_cast<Id>(pair.a);
        end_view(i, 1) = static_cast<Id>(pair.b);
        for (int k = 0; k < Dim; ++k) shift_view(i, k) = pair.shift[static_cast<std::size_t>(k)];
    }
    return py::make_tuple(ends, shifts);
}

}  // namespace smb::python
