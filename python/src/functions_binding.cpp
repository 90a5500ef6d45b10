// SPDX-License-Identifier: MIT
// smb.find_overlapping_pairs: one-shot detection within one set of boxes, or between two.

#include <cstddef>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "smb/join.hpp"
#include "smb/world.hpp"

namespace smb::python {

namespace {

template <std::floating_point Real, int Dim>
py::array_t<std::int64_t> pairs_within(py::handle boxes, const WorldSettings& settings) {
    const auto input = box_array<Real, Dim>(boxes, "boxes");
    std::vector<Pair> pairs;
    {
        py::gil_scoped_release unlocked;
        pairs = find_overlapping_pairs<Real, Dim>(input.boxes, settings);
        sort_pairs(pairs);
    }
    return pair_array<std::int64_t>(std::move(pairs));
}

template <std::floating_point Real, int Dim>
py::array_t<std::int64_t> pairs_between(py::handle first, py::handle second, const WorldSettings& settings) {
    const auto a = box_array<Real, Dim>(first, "a_boxes");
    const auto b = box_array<Real, Dim>(second, "b_boxes");
    std::vector<Pair> pairs;
    {
        py::gil_scoped_release unlocked;
        pairs = find_overlapping_pairs<Real, Dim>(a.boxes, b.boxes, settings);
    }
    return pair_array<std::int64_t>(std::move(pairs));
}

WorldSettings one_shot_settings(std::size_t threads, std::size_t target_cell_population, std::size_t max_pairs_held) {
    WorldSettings settings;
    settings.threads = threads;
    settings.target_cell_population = target_cell_population;
    settings.max_pairs_held = max_pairs_held;
    return settings;
}

py::array_t<std::int64_t> find_pairs(py::handle boxes, std::size_t threads, std::size_t target_cell_population,
                                     std::size_t max_pairs_held) {
    const py::array array = as_array(boxes);
    const int dim = box_dimension(array, "boxes");
    const auto settings = one_shot_settings(threads, target_cell_population, max_pairs_held);
    // float32 boxes are detected as floats; every other dtype as doubles. The caller's object
    // goes on (not `array`), so that a list's integers are checked as given.
    if (is_float32(array))
        return dim == 2 ? pairs_within<float, 2>(boxes, settings) : pairs_within<float, 3>(boxes, settings);
    return dim == 2 ? pairs_within<double, 2>(boxes, settings) : pairs_within<double, 3>(boxes, settings);
}

py::array_t<std::int64_t> find_pairs_between(py::handle first, py::handle second, std::size_t threads,
                                             std::size_t target_cell_population, std::size_t max_pairs_held) {
    const py::array a = as_array(first);
    const py::array b = as_array(second);
    const int dim = box_dimension(a, "a_boxes");
    if (box_dimension(b, "b_boxes") != dim)
        throw py::value_error("a_boxes and b_boxes must have the same dimension; got shapes " + shape_text(a) +
                              " and " + shape_text(b));
    const auto settings = one_shot_settings(threads, target_cell_population, max_pairs_held);
    // Two float32 sets are detected as floats; otherwise both as doubles (float32 converts exactly).
    if (is_float32(a) && is_float32(b))
        return dim == 2 ? pairs_between<float, 2>(first, second, settings)
                        : pairs_between<float, 3>(first, second, settings);
    return dim == 2 ? pairs_between<double, 2>(first, second, settings)
                    : pairs_between<double, 3>(first, second, settings);
}

}  // namespace

void bind_functions(py::module_& module) {
    const WorldSettings defaults;
    module.def("find_overlapping_pairs", &find_pairs, py::arg("boxes"), py::arg("threads") = defaults.threads,
               py::arg("target_cell_population") = defaults.target_cell_population,
               py::arg("max_pairs_held") = defaults.max_pairs_held,
               "Every overlapping pair (i, j), i < j, of one set of boxes, sorted.");
    module.def("find_overlapping_pairs_between", &find_pairs_between, py::arg("a_boxes"), py::arg("b_boxes"),
               py::arg("threads") = defaults.threads,
               py::arg("target_cell_population") = defaults.target_cell_population,
               py::arg("max_pairs_held") = defaults.max_pairs_held,
               "Every pair (i, j) with a_boxes[i] overlapping b_boxes[j], sorted.");
}

}  // namespace smb::python
