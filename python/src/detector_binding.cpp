// SPDX-License-Identifier: MIT
// smb.Detector's compiled classes: Detector2f, Detector2d, Detector3f, Detector3d.

#include <pybind11/stl.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "periodic_arrays.hpp"
#include "smb/detector.hpp"

namespace smb::python {

namespace {

/// A Detector with the PairEvents it feeds, when asked for at construction.
template <std::floating_point Real, int Dim>
struct DetectorHandle {
    DetectorHandle(const DetectorSettings& settings, bool with_events, unsigned event_threads) : detector(settings) {
        if (with_events) events = std::make_unique<PairEvents>(event_threads);
    }

    PairEvents& checked_events() const {
        if (!events) throw std::runtime_error("pair events are off; construct the Detector with events=True");
        return *events;
    }

    /// A vector for the next detection's pairs, with room for as many as the last one found and
    /// an eighth more. Each detection hands its vector over to the array it returns, so the
    /// next one starts empty; grown by doubling, it would copy its pairs and fault in fresh pages
    /// about twice over (at 2 million pairs that tripled the call beside the C++ one).
    [[nodiscard]] std::vector<Pair> pair_buffer() const {
        std::vector<Pair> pairs;
        pairs.reserve(last_pair_count + last_pair_count / 8);
        return pairs;
    }

    Detector<Real, Dim> detector;
    std::unique_ptr<PairEvents> events;
    std::size_t last_pair_count = 0;
    /// The pairs of the detections that write into the caller's buffer (out=): kept from call
    /// to call, so that its pages stay mapped, as a C++ caller's reused vector.
    std::vector<Pair> reused;
    /// Mutable: reads take it too, since a detection in another thread changes what they read.
    mutable BusyFlag busy;
};

template <std::floating_point Real, int Dim>
py::array detect(DetectorHandle<Real, Dim>& self, py::handle boxes, py::handle categories, py::handle masks,
                 py::handle statics, bool sort, py::handle out) {
    const py::array buffer = out.is_none() ? py::array() : pair_buffer_array<std::int64_t>(out);
    const auto input = box_array<Real, Dim>(boxes, "boxes");
    const std::size_t count = input.boxes.size();
    const std::vector<Filter> filters = filter_values(categories, masks, count);
    const std::vector<std::uint8_t> static_flags =
        statics.is_none() ? std::vector<std::uint8_t>{} : flag_values(statics, count, "static");
    const BusyScope busy(self.busy, "this Detector");
    std::vector<Pair> pairs = out.is_none() ? self.pair_buffer() : std::move(self.reused);
    pairs.clear();
    {
        py::gil_scoped_release unlocked;
        try {
            if (!filters.empty() || !static_flags.empty()) {
                const DetectFilters detect_filters{filters, static_flags, {}};
                self.detector.detect(input.boxes, detect_filters, pairs);
                if (self.events) self.events->update(pairs);
            } else if (self.events) {
                self.detector.detect(input.boxes, pairs, *self.events);
            } else {
                self.detector.detect(input.boxes, pairs);
            }
        } catch (...) {
            if (!out.is_none()) self.reused = std::move(pairs);
            throw;
        }
        if (sort) sort_pairs(pairs);
    }
    self.last_pair_count = pairs.size();
    if (out.is_none()) return pair_array<std::int64_t>(std::move(pairs));
    self.reused = std::move(pairs);
    return pairs_into<std::int64_t>(buffer, self.reused);
}

/// (pairs, margin, available) of Detector::candidates(), the pairs copied (they live only until
/// the next detection).
template <std::floating_point Real, int Dim>
py::tuple candidates(DetectorHandle<Real, Dim>& self) {
    const BusyScope busy(self.busy, "this Detector");
    const CandidatePairs list = self.detector.candidates();
    return py::make_tuple(pair_array_copy<std::int64_t>(list.pairs), list.margin, list.available);
}

template <std::floating_point Real, int Dim>
py::tuple detect_periodic(DetectorHandle<Real, Dim>& self, py::handle boxes, py::handle lo, py::handle hi,
                          py::handle axes, bool sort) {
    const auto input = box_array<Real, Dim>(boxes, "boxes");
    const auto domain = periodic_domain<Real, Dim>(lo, hi, axes);
    const BusyScope busy(self.busy, "this Detector");
    std::vector<PeriodicPair> pairs;
    {
        py::gil_scoped_release unlocked;
        if (self.events)
            self.detector.detect(input.boxes, domain, pairs, *self.events);
        else
            self.detector.detect(input.boxes, domain, pairs);
        if (sort) sort_periodic_pairs(pairs);
    }
    return periodic_result<Dim, std::int64_t>(pairs);
}

template <std::floating_point Real, int Dim>
void bind_detector(py::module_& module) {
    using Handle = DetectorHandle<Real, Dim>;
    py::class_<Handle>(module, ("Detector" + type_suffix<Real, Dim>()).c_str())
        .def(py::init([](double skin, std::size_t threads, std::size_t target_cell_population,
                         std::size_t max_pairs_held, bool events, bool profile) {
                 DetectorSettings settings;
                 settings.skin = skin;
                 settings.profile = profile;
                 settings.threads = threads;
                 settings.target_cell_population = target_cell_population;
                 settings.max_pairs_held = max_pairs_held;
                 return std::make_unique<Handle>(settings, events, static_cast<unsigned>(threads));
             }),
             py::arg("skin"), py::arg("threads"), py::arg("target_cell_population"), py::arg("max_pairs_held"),
             py::arg("events"), py::arg("profile") = false)
        .def("detect", &detect<Real, Dim>, py::arg("boxes"), py::arg("categories") = py::none(),
             py::arg("masks") = py::none(), py::arg("static") = py::none(), py::arg("sort") = false,
             py::arg("out") = py::none())
        .def("candidates", &candidates<Real, Dim>)
        .def("suggested_order",
             [](const Handle& self) {
                 const BusyScope busy(self.busy, "this Detector");
                 const std::span<const std::uint32_t> order = self.detector.suggested_order();
                 py::array_t<std::int64_t> out(static_cast<py::ssize_t>(order.size()));
                 std::int64_t* written = out.mutable_data();
                 for (std::size_t i = 0; i < order.size(); ++i) written[i] = order[i];
                 return out;
             })
        .def("follow_suggested_order",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "this Detector");
                 self.detector.follow_suggested_order();
             })
        .def("detect_periodic", &detect_periodic<Real, Dim>, py::arg("boxes"), py::arg("lo"), py::arg("hi"),
             py::arg("axes") = py::none(), py::arg("sort") = false)
        .def_property_readonly("begun",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return pair_array_copy<std::int64_t>(self.checked_events().begun());
                               })
        .def_property_readonly("ended",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return pair_array_copy<std::int64_t>(self.checked_events().ended());
                               })
        .def("swap_remove",
             [](Handle& self, py::handle removed, py::handle last) {
                 const BoxId removed_index = single_id(removed, "removed");
                 const BoxId last_index = single_id(last, "last");
                 const BusyScope busy(self.busy, "this Detector");
                 self.checked_events().swap_remove(removed_index, last_index);
             })
        .def("replace",
             [](Handle& self, py::handle indices) {
                 const auto ids = id_array(indices, "indices");
                 const BusyScope busy(self.busy, "this Detector");
                 PairEvents& events = self.checked_events();
                 for (const BoxId id : ids.ids) events.replace(id);
             })
        .def("replace_all",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "this Detector");
                 self.checked_events().replace_all();
             })
        .def("clear",
             [](Handle& self) {
                 const BusyScope busy(self.busy, "this Detector");
                 self.detector.clear();
             })
        .def_property_readonly("stats",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return stats_dict(self.detector.last_stats());
                               })
        .def_property_readonly("profile",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return profile_dict(self.detector.last_profile());
                               })
        .def_property_readonly("precision",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return precision_name(self.detector.last_precision());
                               })
        .def_property_readonly("retested_pairs",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return self.detector.last_retested_pairs();
                               })
        .def_property_readonly("bytes_held",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return self.detector.bytes_held();
                               })
        .def_property_readonly("skin",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return self.detector.settings().skin;
                               })
        .def_property_readonly("threads",
                               [](const Handle& self) {
                                   const BusyScope busy(self.busy, "this Detector");
                                   return self.detector.settings().threads;
                               })
        .def_property_readonly("events_enabled", [](const Handle& self) {
            const BusyScope busy(self.busy, "this Detector");
            return self.events != nullptr;
        });
}

}  // namespace

void bind_detectors(py::module_& module) {
    bind_detector<float, 2>(module);
    bind_detector<double, 2>(module);
    bind_detector<float, 3>(module);
    bind_detector<double, 3>(module);
}

}  // namespace smb::python
