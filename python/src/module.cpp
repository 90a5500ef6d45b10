// SPDX-License-Identifier: MIT
// The compiled part of the Python package smb: smb/__init__.py wraps it in the public names.

#include <pybind11/pybind11.h>

#include <string>

#include "bindings.hpp"
#include "smb/errors.hpp"
#include "smb/settings.hpp"

namespace smb::python {

py::dict stats_dict(const DetectStats& stats) {
    py::dict dict;
    dict["boxes"] = stats.boxes;
    dict["pairs"] = stats.pairs;
    dict["bytes_held"] = stats.bytes_held;
    dict["total_seconds"] = stats.total_seconds;
    dict["skin_candidates"] = stats.skin_candidates;
    dict["skin_refreshed"] = stats.skin_refreshed;
    dict["skin_rebuilt"] = stats.skin_rebuilt;
    dict["static_contacts"] = stats.static_contacts;
    dict["static_refreshed"] = stats.static_refreshed;
    dict["statics_rebuilt"] = stats.statics_rebuilt;
    return dict;
}

py::dict profile_dict(const DetectProfile& profile) {
    auto listed = [](const auto& values) {
        py::list list;
        for (const auto value : values) list.append(value);
        return list;
    };
    py::dict dict;
    dict["update_seconds"] = profile.update_seconds;
    dict["scan_seconds"] = profile.scan_seconds;
    dict["containment_seconds"] = profile.containment_seconds;
    dict["quantile_seconds"] = profile.quantile_seconds;
    dict["list_sort_seconds"] = profile.list_sort_seconds;
    dict["cut_regroup_seconds"] = profile.cut_regroup_seconds;
    dict["check_seconds"] = profile.check_seconds;
    dict["copy_seconds"] = profile.copy_seconds;
    dict["level_seconds"] = listed(profile.level_seconds);
    dict["cells"] = profile.cells;
    dict["oversized_boxes"] = profile.oversized_boxes;
    dict["sort_moves"] = profile.sort_moves;
    dict["level_sort_moves"] = listed(profile.level_sort_moves);
    dict["level_sort_comparisons"] = listed(profile.level_sort_comparisons);
    dict["level_singular_items"] = listed(profile.level_singular_items);
    dict["level_sort_fallback_items"] = listed(profile.level_sort_fallback_items);
    dict["largest_cell_boxes"] = profile.largest_cell_boxes;
    return dict;
}

const char* precision_name(HeldPrecision precision) {
    switch (precision) {
        case HeldPrecision::floats:
            return "floats";
        case HeldPrecision::doubles:
            return "doubles";
        case HeldPrecision::none:
            break;
    }
    return "none";
}

std::string python_pair_limit_message(const std::string& message) {
    std::string text = message.substr(0, message.find("; use "));
    // The setting by its Python name, an argument, not a C++ struct's field.
    for (const std::string cpp_name : {"WorldSettings::max_pairs_held", "DetectorSettings::max_pairs_held"})
        if (const std::size_t at = text.find(cpp_name); at != std::string::npos)
            text.replace(at, cpp_name.size(), "max_pairs_held");
    return text +
           "; raise max_pairs_held (an argument of the object or function) if the memory allows, or detect "
           "over fewer boxes at a time";
}

}  // namespace smb::python

PYBIND11_MODULE(_smb, module) {
    namespace py = pybind11;
    using namespace smb::python;
    module.doc() = "The compiled part of smb; use the names of the smb package.";

    // Base first: pybind11 tries the translators last registered first, so each subclass is
    // caught as itself before the base would take it.
    const auto error = py::register_exception<smb::Error>(module, "Error", PyExc_ValueError);
    py::register_exception<smb::InvalidBoxError>(module, "InvalidBoxError", error);
    py::register_exception<smb::UnknownIdError>(module, "UnknownIdError", error);
    py::register_exception<smb::DuplicateIdError>(module, "DuplicateIdError", error);
    static auto& pair_limit = py::register_exception<smb::PairLimitError>(module, "PairLimitError", error);
    py::register_exception<smb::ArgumentError>(module, "ArgumentError", error);
    // Tried before the one above: the library's message ends by naming its streaming call,
    // which Python does not have; Python is told what it has instead.
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const smb::PairLimitError& limit) {
            pair_limit(python_pair_limit_message(limit.what()).c_str());
        }
    });

    module.def("openmp_enabled", &smb::openmp_enabled, "True when detect() can use more than one thread.");

    bind_functions(module);
    bind_detectors(module);
    bind_worlds(module);
    bind_world_queries(module);
    bind_box_indexes(module);
    bind_pair_events(module);
}
