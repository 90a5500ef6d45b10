// SPDX-License-Identifier: MIT
// The World's region queries and ray casts, added to the classes world_binding.cpp made.

#include <algorithm>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "ray_arrays.hpp"
#include "world_handle.hpp"

namespace smb::python {

namespace {

template <std::floating_point Real, int Dim>
py::array_t<std::uint64_t> query_box(WorldHandle<Real, Dim>& self, py::handle box) {
    const Box<Real, Dim> query = single_box<Real, Dim>(box, "box");
    const BusyScope busy(self.busy, "this World");
    std::vector<BoxId> ids;
    {
        py::gil_scoped_release unlocked;
        self.world.query(query, ids);
        std::sort(ids.begin(), ids.end());
    }
    return id_result<std::uint64_t>(std::move(ids));
}

template <std::floating_point Real, int Dim>
py::array_t<std::uint64_t> query_batch(WorldHandle<Real, Dim>& self, py::handle boxes) {
    const auto queries = box_array<Real, Dim>(boxes, "boxes");
    const BusyScope busy(self.busy, "this World");
    std::vector<QueryHit> hits;
    {
        py::gil_scoped_release unlocked;
        self.world.query(queries.boxes, hits);
        std::sort(hits.begin(), hits.end());
    }
    return query_hit_array<std::uint64_t>(hits);
}

template <std::floating_point Real, int Dim>
py::tuple cast_ray(WorldHandle<Real, Dim>& self, py::handle origin, py::handle direction, double max_t, bool all) {
    const auto ray = make_ray<Real, Dim>(origin, direction, max_t);
    const BusyScope busy(self.busy, "this World");
    std::vector<RayHit<Real>> hits;
    self.world.cast_ray(ray, all ? RayHits::all : RayHits::nearest, hits);
    return ray_result<std::uint64_t>(hits);
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
