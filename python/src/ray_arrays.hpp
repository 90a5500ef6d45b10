// SPDX-License-Identifier: MIT
#pragma once
// Rays from Python arguments, and what region queries and ray casts find back as arrays, for
// every object that answers them (World, BoxIndex).

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "arrays.hpp"
#include "smb/query.hpp"

namespace smb::python {

/// The ray origin + t * direction, 0 <= t <= max_t, in the object's dtype; TypeError when
/// max_t does not convert exactly (the library checks the ray itself: ArgumentError).
template <std::floating_point Real, int Dim>
Ray<Real, Dim> make_ray(py::handle origin, py::handle direction, double max_t) {
    Ray<Real, Dim> ray;
    ray.origin = coordinates<Real, Dim>(origin, "origin");
    ray.direction = coordinates<Real, Dim>(direction, "direction");
    ray.max_t = static_cast<Real>(max_t);
    if (std::isfinite(max_t) && static_cast<double>(ray.max_t) != max_t)
        throw py::type_error("max_t does not convert exactly to the object's dtype");
    return ray;
}

/// (ids, t): the hits' ids (dtype Id) and entry parameters (dtype Real), in the order found.
template <OutputId Id, std::floating_point Real>
py::tuple ray_result(const std::vector<RayHit<Real>>& hits) {
    const auto count = static_cast<py::ssize_t>(hits.size());
    py::array_t<Id> ids(count);
    py::array_t<Real> ts(count);
    for (py::ssize_t i = 0; i < count; ++i) {
        ids.mutable_data()[i] = static_cast<Id>(hits[static_cast<std::size_t>(i)].id);
        ts.mutable_data()[i] = hits[static_cast<std::size_t>(i)].t;
    }
    return py::make_tuple(ids, ts);
}

/// (H, 2) array of (query index, id) rows, dtype Id, from hits sorted by the caller.
template <OutputId Id>
py::array_t<Id> query_hit_array(const std::vector<QueryHit>& hits) {
    py::array_t<Id> array({static_cast<py::ssize_t>(hits.size()), py::ssize_t{2}});
    auto view = array.template mutable_unchecked<2>();
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        view(row, 0) = static_cast<Id>(hits[i].query);
        view(row, 1) = static_cast<Id>(hits[i].id);
    }
    return array;
}

}  // namespace smb::python
