// SPDX-License-Identifier: MIT
// The World's region queries and ray casts, added to the classes world_binding.cpp made.

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "world_handle.hpp"

namespace smb::python {

namespace {

template <std::floating_point Real, int Dim>
py::array_t<std::int64_t> query_box(WorldHandle<Real, Dim>& self, py::handle box) {
    const Box<Real, Dim> query = single_box<Real, Dim>(box, "box");
    const BusyScope busy(self.busy, "this World");
    std::vector<BoxId> ids;
    {
        py::gil_scoped_release unlocked;
        self.world.query(query, ids);
        std::sort(ids.begin(), ids.end());
    }
    return id_result(std::move(ids));
}

template <std::floating_point Real, int Dim>
py::array_t<std::int64_t> query_batch(WorldHandle<Real, Dim>& self, py::handle boxes) {
    const auto queries = box_array<Real, Dim>(boxes, "boxes");
    const BusyScope busy(self.busy, "this World");
    std::vector<QueryHit> hits;
    {
        py::gil_scoped_release unlocked;
        self.world.query(queries.boxes, hits);
        std::sort(hits.begin(), hits.end());
    }
    py::array_t<std::int64_t> array({static_cast<py::ssize_t>(hits.size()), py::ssize_t{2}});
    auto view = array.mutable_unchecked<2>();
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const auto row = static_cast<py::ssize_t>(i);
        view(row, 0) = static_cast<std::int64_t>(hits[i].query);
        view(row, 1) = static_cast<std::int64_t>(hits[i].id);
    }
    return array;
}

template <std::floating_point Real, int Dim>
py::tuple cast_ray(WorldHandle<Real, Dim>& self, py::handle origin, py::handle direction, double max_t, bool all) {
    Ray<Real, Dim> ray;
    ray.origin = coordinates<Real, Dim>(origin, "origin");
    ray.direction = coordinates<Real, Dim>(direction, "direction");
    ray.max_t = static_cast<Real>(max_t);
    if (std::isfinite(max_t) && static_cast<double>(ray.max_t) != max_t)
        throw py::type_error("max_t does not convert exactly to the world's dtype");
    const BusyScope busy(self.busy, "this World");
    std::vector<RayHit<Real>> hits;
    self.world.cast_ray(ray, all ? RayHits::all : RayHits::nearest, hits);
    const auto count = static_cast<py::ssize_t>(hits.size());
    py::array_t<std::int64_t> ids(count);
    py::array_t<Real> ts(count);
    for (py::ssize_t i = 0; i < count; ++i) {
        ids.mutable_data()[i] = static_cast<std::int64_t>(hits[static_cast<std::size_t>(i)].id);
        ts.mutable_data()[i] = hits[static_cast<std::size_t>(i)].t;
    }
    return py::make_tuple(ids, ts);
}

template <std::floating_point Real, int Dim>
void bind_queries(py::module_& module) {
    using Handle = WorldHandle<Real, Dim>;
    auto cls = py::reinterpret_borrow<py::class_<Handle>>(module.attr(world_class_name<Real, Dim>().c_str()));
    cls.def("query", &query_box<Real, Dim>, py::arg("box"))
        .def("query_batch", &query_batch<Real, Dim>, py::arg("boxes"))
        .def("cast_ray", &cast_ray<Real, Dim>, py::arg("origin"), py::arg("direction"),
             py::arg("max_t") = std::numeric_limits<double>::infinity(), py::arg("all") = false);
}

}  // namespace

void bind_world_queries(py::module_& module) {
    bind_queries<float, 2>(module);
    bind_queries<double, 2>(module);
    bind_queries<float, 3>(module);
    bind_queries<double, 3>(module);
}

}  // namespace smb::python
