// SPDX-License-Identifier: MIT
// smb.BoxIndex's compiled classes (BoxIndex2f ... BoxIndex3d): region queries and ray casts
// over an array of boxes, indexed once.

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "ray_arrays.hpp"
#include "smb/box_index.hpp"

namespace smb::python {

namespace {

/// A BoxIndex, and whether its boxes were given ids (answered as uint64) or are named by their
/// index (answered as int64).
template <std::floating_point Real, int Dim>
struct BoxIndexHandle {
    BoxIndex<Real, Dim> index;
    bool named = false;
    /// Mutable: queries take it too, since a build in another thread changes what they read.
    mutable BusyFlag busy;
};

template <std::floating_point Real, int Dim>
void build(BoxIndexHandle<Real, Dim>& self, py::handle boxes, py::handle ids) {
    const auto input = box_array<Real, Dim>(boxes, "boxes");
    const bool named = !ids.is_none();
    const IdArray names = named ? id_array(ids, "ids") : IdArray{};
    if (named && names.ids.size() != input.boxes.size())
        throw py::value_error(std::to_string(names.ids.size()) + " ids but " + std::to_string(input.boxes.size()) +
                              " boxes; one id per box expected");
    const BusyScope busy(self.busy, "this BoxIndex");
    {
        py::gil_scoped_release unlocked;
        if (named)
            self.index.build(names.ids, input.boxes);
        else
            self.index.build(input.boxes);
    }
    self.named = named;
}

template <std::floating_point Real, int Dim>
py::array query_box(const BoxIndexHandle<Real, Dim>& self, py::handle box) {
    const Box<Real, Dim> query = single_box<Real, Dim>(box, "box");
    const BusyScope busy(self.busy, "this BoxIndex");
    std::vector<BoxId> ids;
    {
        py::gil_scoped_release unlocked;
        self.index.query(query, ids);
        std::sort(ids.begin(), ids.end());
    }
    if (self.named) return id_result<std::uint64_t>(std::move(ids));
    return id_result<std::int64_t>(std::move(ids));
}

template <std::floating_point Real, int Dim>
py::array query_batch(const BoxIndexHandle<Real, Dim>& self, py::handle boxes) {
    const auto queries = box_array<Real, Dim>(boxes, "boxes");
    const BusyScope busy(self.busy, "this BoxIndex");
    std::vector<QueryHit> hits;
    {
        py::gil_scoped_release unlocked;
        self.index.query(queries.boxes, hits);
        std::sort(hits.begin(), hits.end());
    }
    if (self.named) return query_hit_array<std::uint64_t>(hits);
    return query_hit_array<std::int64_t>(hits);
}

template <std::floating_point Real, int Dim>
py::tuple cast_ray(const BoxIndexHandle<Real, Dim>& self, py::handle origin, py::handle direction, double max_t,
                   bool all) {
    const auto ray = make_ray<Real, Dim>(origin, direction, max_t);
    const BusyScope busy(self.busy, "this BoxIndex");
    std::vector<RayHit<Real>> hits;
    {
        py::gil_scoped_release unlocked;
        self.index.cast_ray(ray, all ? RayHits::all : RayHits::nearest, hits);
    }
    if (self.named) return ray_result<std::uint64_t>(hits);
    return ray_result<std::int64_t>(hits);
}

template <std::floating_point Real, int Dim>
void bind_box_index(py::module_& module) {
    using Handle = BoxIndexHandle<Real, Dim>;
    py::class_<Handle>(module, ("BoxIndex" + type_suffix<Real, Dim>()).c_str())
        .def(py::init<>())
        .def("build", &build<Real, Dim>, py::arg("boxes"), py::arg("ids") = py::none())
        .def("query", &query_box<Real, Dim>, py::arg("box"))
        .def("query_batch", &query_batch<Real, Dim>, py::arg("boxes"))
        .def("cast_ray", &cast_ray<Real, Dim>, py::arg("origin"), py::arg("direction"),
             py::arg("max_t") = std::numeric_limits<double>::infinity(), py::arg("all") = false)
        .def("size",
             [](const Handle& self) {
                 const BusyScope busy(self.busy, "this BoxIndex");
                 return self.index.size();
             })
        .def_property_readonly("named",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this BoxIndex");
                                   return self.named;
                               })
        .def_property_readonly("bytes_held", [](const Handle& self) {
            const BusyScope busy(self.busy, "this BoxIndex");
            return self.index.bytes_held();
        });
}

}  // namespace

void bind_box_indexes(py::module_& module) {
    bind_box_index<float, 2>(module);
    bind_box_index<double, 2>(module);
    bind_box_index<float, 3>(module);
    bind_box_index<double, 3>(module);
}

}  // namespace smb::python
