// SPDX-License-Identifier: MIT
// smb.World's compiled classes (World2f ... World3d): changes, detection, filters, statics.

#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "periodic_arrays.hpp"
#include "world_handle.hpp"

namespace smb::python {

namespace {

Pipeline pipeline_named(const std::string& name) {
    if (name == "persistent_cuts") return Pipeline::persistent_cuts;
    if (name == "paper_lists") return Pipeline::paper_lists;
    throw py::value_error("pipeline must be 'persistent_cuts' or 'paper_lists'; got '" + name + "'");
}

template <std::floating_point Real, int Dim>
void insert_or_update(WorldHandle<Real, Dim>& self, py::handle ids, py::handle boxes, bool insert) {
    const auto id_input = id_array(ids, "ids");
    const auto box_input = box_array<Real, Dim>(boxes, "boxes");
    if (id_input.ids.size() != box_input.boxes.size())
        throw py::value_error(std::to_string(id_input.ids.size()) + " ids but " +
                              std::to_string(box_input.boxes.size()) + " boxes; one id per box expected");
    const BusyScope busy(self.busy, "this World");
    py::gil_scoped_release unlocked;
    if (insert)
        self.world.insert(id_input.ids, box_input.boxes);
    else
        self.world.update(id_input.ids, box_input.boxes);
}

template <std::floating_point Real, int Dim>
py::array detect(WorldHandle<Real, Dim>& self, bool sort, py::handle out) {
    const py::array buffer = out.is_none() ? py::array() : pair_buffer_array<std::uint64_t>(out);
    const BusyScope busy(self.busy, "this World");
    std::vector<Pair> pairs = out.is_none() ? self.pair_buffer() : std::move(self.reused);
    pairs.clear();
    {
        py::gil_scoped_release unlocked;
        try {
            if (self.events)
                self.world.detect(pairs, *self.events);
            else
                self.world.detect(pairs);
        } catch (...) {
            if (!out.is_none()) self.reused = std::move(pairs);
            throw;
        }
        if (sort) sort_pairs(pairs);
    }
    self.last_pair_count = pairs.size();
    if (out.is_none()) return pair_array<std::uint64_t>(std::move(pairs));
    self.reused = std::move(pairs);
    return pairs_into<std::uint64_t>(buffer, self.reused);
}

template <std::floating_point Real, int Dim>
py::tuple detect_periodic(WorldHandle<Real, Dim>& self, py::handle lo, py::handle hi, py::handle axes, bool sort) {
    const auto domain = periodic_domain<Real, Dim>(lo, hi, axes);
    const BusyScope busy(self.busy, "this World");
    std::vector<PeriodicPair> pairs;
    {
        py::gil_scoped_release unlocked;
        if (self.events)
            self.world.detect(domain, pairs, *self.events);
        else
            self.world.detect(domain, pairs);
        if (sort) sort_periodic_pairs(pairs);
    }
    return periodic_result<Dim, std::uint64_t>(pairs);
}

template <std::floating_point Real, int Dim>
void set_filter(WorldHandle<Real, Dim>& self, py::handle ids, py::handle categories, py::handle masks) {
    const auto id_input = id_array(ids, "ids");
    std::vector<Filter> filters = filter_values(categories, masks, id_input.ids.size());
    if (filters.empty()) filters.resize(id_input.ids.size());
    const BusyScope busy(self.busy, "this World");
    self.world.set_filter(id_input.ids, filters);
}

template <std::floating_point Real, int Dim>
py::array_t<Real> box_of(const WorldHandle<Real, Dim>& self, py::handle id) {
    const BoxId key = single_id(id, "id");
    const BusyScope busy(self.busy, "this World");
    const Box<Real, Dim> box = self.world.box(key);
    py::array_t<Real> array({py::ssize_t{2}, py::ssize_t{Dim}});
    std::memcpy(array.mutable_data(), &box, sizeof box);
    return array;
}

template <std::floating_point Real, int Dim>
void bind_world(py::module_& module) {
    using Handle = WorldHandle<Real, Dim>;
    auto busy_call = [](auto member) {
        return [member](Handle& self, py::handle ids) {
            const auto id_input = id_array(ids, "ids");
            const BusyScope busy(self.busy, "this World");
            py::gil_scoped_release unlocked;
            member(self.world, id_input.ids);
        };
    };
    py::class_<Handle>(module, world_class_name<Real, Dim>().c_str())
        .def(py::init([](std::size_t threads, std::size_t target_cell_population, std::size_t max_pairs_held,
                         const std::string& pipeline, bool events, double skin, bool profile) {
                 WorldSettings settings;
                 settings.skin = skin;
                 settings.profile = profile;
                 settings.threads = threads;
                 settings.target_cell_population = target_cell_population;
                 settings.max_pairs_held = max_pairs_held;
                 settings.pipeline = pipeline_named(pipeline);
                 return std::make_unique<Handle>(settings, events, static_cast<unsigned>(threads));
             }),
             py::arg("threads"), py::arg("target_cell_population"), py::arg("max_pairs_held"), py::arg("pipeline"),
             py::arg("events"), py::arg("skin") = 0.0, py::arg("profile") = false)
        .def("insert", [](Handle& self, py::handle ids, py::handle boxes) { insert_or_update(self, ids, boxes, true); })
        .def("update",
             [](Handle& self, py::handle ids, py::handle boxes) { insert_or_update(self, ids, boxes, false); })
        .def("remove", busy_call([](World<Real, Dim>& world, std::span<const BoxId> ids) { world.remove(ids); }))
        .def("assign",
             [](Handle& self, py::handle boxes) {
                 const auto input = box_array<Real, Dim>(boxes, "boxes");
                 const BusyScope busy(self.busy, "this World");
                 py::gil_scoped_release unlocked;
                 self.world.assign(input.boxes);
             })
        .def("clear",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "this World");
                 self.world.clear();
             })
        .def("contains",
             [](const Handle& self, py::handle id) {
                 // Membership: anything that cannot be an id is simply not in the world.
                 const std::optional<BoxId> key = id_if_valid(id);
                 const BusyScope busy(self.busy, "this World");
                 return key.has_value() && self.world.contains(*key);
             })
        .def("box", &box_of<Real, Dim>)
        .def("size",
             [](const Handle& self) {
                 const BusyScope busy(self.busy, "this World");
                 return self.world.size();
             })
        .def("detect", &detect<Real, Dim>, py::arg("sort") = false, py::arg("out") = py::none())
        .def("detect_periodic", &detect_periodic<Real, Dim>, py::arg("lo"), py::arg("hi"), py::arg("axes") = py::none(),
             py::arg("sort") = false)
        .def_property_readonly("begun",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return pair_array_copy<std::uint64_t>(self.checked_events().begun());
                               })
        .def_property_readonly("ended",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return pair_array_copy<std::uint64_t>(self.checked_events().ended());
                               })
        .def("set_filter", &set_filter<Real, Dim>, py::arg("ids"), py::arg("categories") = py::none(),
             py::arg("masks") = py::none())
        .def("filter",
             [](const Handle& self, py::handle id) {
                 const BoxId key = single_id(id, "id");
                 const BusyScope busy(self.busy, "this World");
                 const Filter filter = self.world.filter(key);
                 return py::make_tuple(filter.category, filter.mask);
             })
        .def("set_static",
             [](Handle& self, py::handle ids, bool is_static) {
                 const auto id_input = id_array(ids, "ids");
                 const BusyScope busy(self.busy, "this World");
                 self.world.set_static(id_input.ids, is_static);
             })
        .def("is_static",
             [](const Handle& self, py::handle id) {
                 const BoxId key = single_id(id, "id");
                 const BusyScope busy(self.busy, "this World");
                 return self.world.is_static(key);
             })
        .def_property_readonly("stats",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return stats_dict(self.world.last_stats());
                               })
        .def_property_readonly("profile",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return profile_dict(self.world.last_profile());
                               })
        .def_property_readonly("precision",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return precision_name(self.world.last_precision());
                               })
        .def_property_readonly("retested_pairs",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return self.world.last_retested_pairs();
                               })
        .def_property_readonly("bytes_held",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return self.world.bytes_held();
                               })
        .def_property_readonly("threads",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this World");
                                   return self.world.settings().threads;
                               })
        .def_property_readonly("events_enabled", [](const Handle& self) {
            const BusyScope busy(self.busy, "this World");
            return self.events != nullptr;
        });
}

}  // namespace

void bind_worlds(py::module_& module) {
    bind_world<float, 2>(module);
    bind_world<double, 2>(module);
    bind_world<float, 3>(module);
    bind_world<double, 3>(module);
}

}  // namespace smb::python
