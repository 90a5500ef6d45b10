// SPDX-License-Identifier: MIT
#pragma once
// NumPy arrays in and out of the binding: boxes and ids read in place where their layout
// allows it, pairs handed to Python without a copy.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "smb/box.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::python {

namespace py = pybind11;

/// The boxes of one call: a span over the caller's array when it is C-contiguous, aligned and
/// of the right dtype, else over a converted copy that `array` keeps alive.
template <std::floating_point Real, int Dim>
struct BoxArray {
    py::array array;
    std::span<const Box<Real, Dim>> boxes;
};

/// `obj` as a NumPy array (numpy.asarray), so that lists and other buffers are accepted too.
py::array as_array(py::handle obj);

/// The dimension of an array of boxes: 2 or 3 from its shape, (N, 2, D) or (N, 2*D); throws
/// ValueError naming `what` and the shapes expected.
int box_dimension(const py::array& array, const char* what);

/// True when `array`'s dtype is exactly float32 (so its boxes are read as floats).
bool is_float32(const py::array& array);

/// Reads `obj` as boxes of Real in Dim dimensions. The shape must be (N, 2, Dim) or
/// (N, 2*Dim), rows min then max; the dtype Real itself or one NumPy casts to it without loss
/// ("safe"). Throws ValueError (shape) or TypeError (dtype) before anything else happens.
template <std::floating_point Real, int Dim>
BoxArray<Real, Dim> box_array(py::handle obj, const char* what);

/// One box of Real in Dim dimensions (shape (2, Dim) or (2*Dim,)), as box_array reads one.
template <std::floating_point Real, int Dim>
Box<Real, Dim> single_box(py::handle obj, const char* what);

/// `Dim` coordinates of Real (a point, a direction, a domain's bounds).
template <std::floating_point Real, int Dim>
std::array<Real, Dim> coordinates(py::handle obj, const char* what);

/// Ids of one call: integers in [0, 2^64), a 1-D array or a single integer. Read in place when
/// the array is C-contiguous uint64, or int64 with no negative entry; an array of Python
/// integers too large for int64 (dtype object) is read one by one. Negative or larger values
/// raise ValueError, other dtypes TypeError.
struct IdArray {
    py::array array;
    std::span<const BoxId> ids;
};
IdArray id_array(py::handle obj, const char* what);

/// `obj` as an array of ids to be read by id_array: as_array, except that a list NumPy would
/// turn into float64 (Python integers at or above 2^63 beside others) becomes an object array.
py::array as_id_array(py::handle obj);

/// One id (a Python or NumPy integer in [0, 2^64)); ValueError or TypeError naming `what`.
BoxId single_id(py::handle obj, const char* what);

/// One id, or nothing when `obj` is not an integer in [0, 2^64) (no box can be under it).
std::optional<BoxId> id_if_valid(py::handle obj);

/// Integers in [0, 2^32) for `count` boxes: a 1-D array of that length or one value for all.
std::vector<std::uint32_t> uint32_values(py::handle obj, std::size_t count, const char* what);

/// Flags for `count` boxes (non-zero: set): a 1-D array of that length or one value for all;
/// `unit` names what each flag is for ("box", "axis").
std::vector<std::uint8_t> flag_values(py::handle obj, std::size_t count, const char* what, const char* unit = "box");

/// The filters of `count` boxes from category and mask values (None: the default, 1 and every
/// bit); empty when both are None.
std::vector<Filter> filter_values(py::handle categories, py::handle masks, std::size_t count);

/// The dtype pairs and ids come back in: int64 for indices (Detector, find_overlapping_pairs),
/// uint64 for ids (World), which may use the whole 64-bit range.
template <class T>
concept OutputId = std::same_as<T, std::int64_t> || std::same_as<T, std::uint64_t>;

/// A (P, 2) array that takes over `pairs` without copying them.
template <OutputId Id>
py::array_t<Id> pair_array(std::vector<Pair>&& pairs);

/// A (P, 2) array holding a copy of `pairs`.
template <OutputId Id>
py::array_t<Id> pair_array_copy(std::span<const Pair> pairs);

/// A 1-D array that takes over `ids` without copying them.
template <OutputId Id>
py::array_t<Id> id_result(std::vector<BoxId>&& ids);

/// `out` checked as a buffer for pairs: a writeable, C-contiguous (M, 2) array of dtype Id.
/// Throws ValueError (shape, layout) or TypeError (dtype) before anything else happens.
template <OutputId Id>
py::array pair_buffer_array(py::handle out);

/// `pairs` copied into the first rows of `out` (checked by pair_buffer_array) and out[:P]
/// returned when they fit; otherwise a new array holding them.
template <OutputId Id>
py::array pairs_into(py::array out, std::span<const Pair> pairs);

/// Throws ValueError saying that `what` has `got` entries where `expected` were needed, one per
/// `unit` ("box", "axis", "id").
void check_count(std::size_t got, std::size_t expected, const char* what, const char* unit = "box");

/// The shape of an array as Python writes it: "(3, 2, 2)".
std::string shape_text(const py::array& array);

}  // namespace smb::python
