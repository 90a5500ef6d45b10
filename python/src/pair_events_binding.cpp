// SPDX-License-Identifier: MIT
// smb.PairEvents's compiled class: contact events over pair lists from any source, as the C++
// PairEvents (include/smb/pair_events.hpp).

#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "smb/pair_events.hpp"

namespace smb::python {

namespace {

struct PairEventsHandle {
    explicit PairEventsHandle(unsigned threads) : events(threads) {}

    PairEvents events;
    mutable BusyFlag busy;
};

/// The pairs of `obj`, a (P, 2) array of names in [0, 2^64), read as smb::Pair: the array that
/// holds them, and the span over it.
struct PairInput {
    IdArray names;
    std::span<const Pair> pairs;
};

PairInput pair_input(py::handle obj) {
    const py::array array = as_id_array(obj);
    const bool empty_list = array.ndim() == 1 && array.shape(0) == 0;
    if (!empty_list && (array.ndim() != 2 || array.shape(1) != 2))
        throw py::value_error("pairs must have shape (P, 2); got shape " + shape_text(array));
    PairInput input{id_array(array.attr("reshape")(-1), "pairs"), {}};
    static_assert(sizeof(Pair) == 2 * sizeof(BoxId) && alignof(Pair) == alignof(BoxId));
    input.pairs =
        std::span<const Pair>(reinterpret_cast<const Pair*>(input.names.ids.data()), input.names.ids.size() / 2);
    return input;
}

}  // namespace

void bind_pair_events(py::module_& module) {
    using Handle = PairEventsHandle;
    py::class_<Handle>(module, "PairEvents")
        .def(py::init<unsigned>(), py::arg("threads"))
        .def(
            "update",
            [](Handle& self, py::handle pairs, py::handle replaced) {
                const PairInput input = pair_input(pairs);
                const IdArray names = replaced.is_none() ? IdArray{} : id_array(replaced, "replaced");
                const BusyScope busy(self.busy, "these PairEvents");
                py::gil_scoped_release unlocked;
                self.events.update(input.pairs, names.ids);
            },
            py::arg("pairs"), py::arg("replaced") = py::none())
        .def("replace",
             [](Handle& self, py::handle names) {
                 const IdArray input = id_array(names, "names");
                 const BusyScope busy(self.busy, "these PairEvents");
                 for (const BoxId name : input.ids) self.events.replace(name);
             })
        .def("replace_all",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "these PairEvents");
                 self.events.replace_all();
             })
        .def("swap_remove",
             [](Handle& self, py::handle removed, py::handle last) {
                 const BoxId removed_name = single_id(removed, "removed");
                 const BoxId last_name = single_id(last, "last");
                 const BusyScope busy(self.busy, "these PairEvents");
                 self.events.swap_remove(removed_name, last_name);
             })
        .def("clear",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "these PairEvents");
                 self.events.clear();
             })
        .def_property_readonly("begun",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "these PairEvents");
                                   return pair_array_copy<std::uint64_t>(self.events.begun());
                               })
        .def_property_readonly("ended",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "these PairEvents");
                                   return pair_array_copy<std::uint64_t>(self.events.ended());
                               })
        .def("size",
             [](const Handle& self) {
                 const BusyScope busy(self.busy, "these PairEvents");
                 return self.events.size();
             })
        .def_property_readonly("threads",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "these PairEvents");
                                   return self.events.threads();
                               })
        .def_property_readonly("bytes_held", [](const Handle& self) {
            const BusyScope busy(self.busy, "these PairEvents");
            return self.events.bytes_held();
        });
}

}  // namespace smb::python
