// SPDX-License-Identifier: MIT
#include "arrays.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace smb::python {

namespace {

py::module_ numpy() { return py::module_::import("numpy"); }

template <std::floating_point Real>
const char* dtype_name() {
    return std::is_same_v<Real, float> ? "float32" : "float64";
}

bool aligned(const py::array& array, std::size_t alignment) {
    return reinterpret_cast<std::uintptr_t>(array.data()) % alignment == 0;
}

/// True when every integer of `array` (dtype Int after a conversion that keeps the values)
/// is a Real exactly. A float64 holds the integers up to 2^53, a float32 those up to 2^24, and
/// beyond that only some; NumPy calls int64 to float64 a "safe" cast all the same.
template <std::floating_point Real, class Int>
bool integers_exact(const py::array& array) {
    const auto values = py::array_t<Int, py::array::c_style | py::array::forcecast>(array);
    // 2^63 or 2^64: the first value past Int, exactly a Real.
    const Real past = std::ldexp(Real{1}, std::numeric_limits<Int>::digits);
    const Int* data = values.data();
    for (py::ssize_t i = 0; i < values.size(); ++i) {
        const auto real = static_cast<Real>(data[i]);
        if (!(real < past) || static_cast<Int>(real) != data[i]) return false;
    }
    return true;
}

/// `array` as C-contiguous Real: itself when it is already that, else a converted copy. A dtype
/// that converts to Real without loss whatever its values is converted; any other integer or
/// float dtype only when every value survives the conversion (so the boxes detected are the
/// caller's boxes).
template <std::floating_point Real>
py::array as_real(const py::array& array, const char* what) {
    const py::dtype wanted = py::dtype::of<Real>();
    if (!array.dtype().equal(wanted)) {
        const py::dtype given = array.dtype();
        const char kind = given.kind();
        if (kind != 'f' && kind != 'i' && kind != 'u')
            throw py::type_error(std::string(what) + " must hold numbers (" + dtype_name<Real>() + "); got dtype " +
                                 py::str(py::object(given)).cast<std::string>());
        bool exact = true;
        if (kind == 'f') {
            if (!py::cast<bool>(numpy().attr("can_cast")(given, wanted, "safe"))) {
                const py::object back = array.attr("astype")(wanted).attr("astype")(given);
                exact = py::cast<bool>(numpy().attr("array_equal")(back, array, py::arg("equal_nan") = true));
            }
        } else {
            const int magnitude_bits = static_cast<int>(8 * given.itemsize()) - (kind == 'i' ? 1 : 0);
            if (magnitude_bits > std::numeric_limits<Real>::digits)
                exact = kind == 'i' ? integers_exact<Real, std::int64_t>(array)
                                    : integers_exact<Real, std::uint64_t>(array);
        }
        if (!exact)
            throw py::type_error(std::string(what) + ": the " + py::str(py::object(given)).cast<std::string>() +
                                 " values do not all convert exactly to " + dtype_name<Real>() +
                                 ", the dtype expected here; convert them first (.astype(numpy." + dtype_name<Real>() +
                                 ")) to accept the rounding");
    }
    py::array result = py::array_t<Real, py::array::c_style | py::array::forcecast>(array);
    // An array over an offset buffer may be misaligned; a fresh copy is not.
    if (!aligned(result, alignof(Real))) result = numpy().attr("array")(result, py::arg("copy") = true);
    return result;
}

template <class Int>
py::array_t<Int, py::array::c_style | py::array::forcecast> as_integers(const py::array& array) {
    return py::array_t<Int, py::array::c_style | py::array::forcecast>(array);
}

/// `array` as integers of type Int, checked to lie in [0, limit].
template <class Int>
py::array_t<Int, py::array::c_style | py::array::forcecast> checked_integers(const py::array& array,
                                                                             std::uint64_t limit, const char* what) {
    auto values = as_integers<Int>(array);
    const Int* data = values.data();
    for (py::ssize_t i = 0; i < values.size(); ++i) {
        if constexpr (std::is_signed_v<Int>) {
            if (data[i] < 0)
                throw py::value_error(std::string(what) + " must not be negative; entry " + std::to_string(i) + " is " +
                                      std::to_string(data[i]));
        }
        if (static_cast<std::uint64_t>(data[i]) > limit)
            throw py::value_error(std::string(what) + ": entry " + std::to_string(i) + " is " +
                                  std::to_string(data[i]) + ", above the largest allowed, " + std::to_string(limit));
    }
    return values;
}

/// `obj` as a 1-D array of `count` entries, a 0-d value broadcast to all of them.
py::array entries_for(py::handle obj, std::size_t count, const char* what, const char* unit = "box") {
    py::array array = as_array(obj);
    if (array.ndim() == 0) return numpy().attr("full")(count, array);
    if (array.ndim() != 1)
        throw py::value_error(std::string(what) + " must be one value or 1-D; got shape " + shape_text(array));
    check_count(static_cast<std::size_t>(array.shape(0)), count, what, unit);
    return array;
}

void check_integer_kind(const py::array& array, const char* what) {
    const char kind = array.dtype().kind();
    if (kind != 'i' && kind != 'u' && !(kind == 'b' && array.size() == 0) && !(kind == 'f' && array.size() == 0))
        throw py::type_error(std::string(what) + " must be integers; got dtype " +
                             py::str(array.dtype()).cast<std::string>());
}

/// Throws TypeError when `obj`, not an array, holds a Python integer that float64 cannot hold
/// exactly: NumPy would have rounded it on making `array` (float64) of it.
void check_python_integers(py::handle obj, const py::array& array, const char* what) {
    if (py::isinstance<py::array>(obj) || array.dtype().kind() != 'f') return;
    const py::array items = numpy().attr("asarray")(obj, py::arg("dtype") = "object");
    for (const py::handle item : items.attr("flat")) {
        if (!PyLong_Check(item.ptr()) || PyBool_Check(item.ptr())) continue;
        const double value = PyLong_AsDouble(item.ptr());
        const bool overflow = value == -1.0 && PyErr_Occurred() != nullptr;
        if (overflow) PyErr_Clear();
        if (overflow || !py::float_(value).equal(item))
            throw py::type_error(std::string(what) + ": the integer " + py::repr(item).cast<std::string>() +
                                 " does not convert exactly to float64; convert it first to accept the rounding");
    }
}

}  // namespace

py::array as_array(py::handle obj) {
    if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
    return numpy().attr("asarray")(obj);
}

std::string shape_text(const py::array& array) {
    std::string text = "(";
    for (py::ssize_t k = 0; k < array.ndim(); ++k) {
        if (k > 0) text += ", ";
        text += std::to_string(array.shape(k));
    }
    if (array.ndim() == 1) text += ",";
    return text + ")";
}

void check_count(std::size_t got, std::size_t expected, const char* what, const char* unit) {
    if (got != expected)
        throw py::value_error(std::string(what) + " has " + std::to_string(got) + " entries; " +
                              std::to_string(expected) + " expected (one per " + unit + ")");
}

int box_dimension(const py::array& array, const char* what) {
    if (array.ndim() == 3 && array.shape(1) == 2 && (array.shape(2) == 2 || array.shape(2) == 3))
        return static_cast<int>(array.shape(2));
    if (array.ndim() == 2 && (array.shape(1) == 4 || array.shape(1) == 6)) return static_cast<int>(array.shape(1) / 2);
    throw py::value_error(std::string(what) +
                          " must have shape (N, 2, D) (rows min, max) or (N, 2*D) (xmin, ymin[, zmin], xmax, "
                          "ymax[, zmax]) with D = 2 or 3; got shape " +
                          shape_text(array));
}

bool is_float32(const py::array& array) { return array.dtype().equal(py::dtype::of<float>()); }

template <std::floating_point Real, int Dim>
BoxArray<Real, Dim> box_array(py::handle obj, const char* what) {
    static_assert(sizeof(Box<Real, Dim>) == 2 * Dim * sizeof(Real) && alignof(Box<Real, Dim>) == alignof(Real),
                  "a box must be its 2*Dim coordinates, min then max, to be read in place");
    const py::array array = as_array(obj);
    const bool shape_ok = (array.ndim() == 3 && array.shape(1) == 2 && array.shape(2) == Dim) ||
                          (array.ndim() == 2 && array.shape(1) == 2 * Dim);
    if (!shape_ok)
        throw py::value_error(std::string(what) + " must have shape (N, 2, " + std::to_string(Dim) + ") or (N, " +
                              std::to_string(2 * Dim) + ") for " + std::to_string(Dim) + "D boxes; got shape " +
                              shape_text(array));
    check_python_integers(obj, array, what);
    py::array held = as_real<Real>(array, what);
    const auto* first = static_cast<const Box<Real, Dim>*>(held.data());
    return {held, std::span<const Box<Real, Dim>>(first, static_cast<std::size_t>(array.shape(0)))};
}

template <std::floating_point Real, int Dim>
Box<Real, Dim> single_box(py::handle obj, const char* what) {
    const py::array array = as_array(obj);
    const bool shape_ok = (array.ndim() == 2 && array.shape(0) == 2 && array.shape(1) == Dim) ||
                          (array.ndim() == 1 && array.shape(0) == 2 * Dim);
    if (!shape_ok)
        throw py::value_error(std::string(what) + " must have shape (2, " + std::to_string(Dim) + ") or (" +
                              std::to_string(2 * Dim) + ",); got shape " + shape_text(array));
    check_python_integers(obj, array, what);
    const py::array held = as_real<Real>(array, what);
    Box<Real, Dim> box;
    std::memcpy(&box, held.data(), sizeof box);
    return box;
}

template <std::floating_point Real, int Dim>
std::array<Real, Dim> coordinates(py::handle obj, const char* what) {
    const py::array array = as_array(obj);
    if (array.ndim() != 1 || array.shape(0) != Dim)
        throw py::value_error(std::string(what) + " must have shape (" + std::to_string(Dim) + ",); got shape " +
                              shape_text(array));
    check_python_integers(obj, array, what);
    const py::array held = as_real<Real>(array, what);
    std::array<Real, Dim> values;
    std::memcpy(values.data(), held.data(), sizeof values);
    return values;
}

std::vector<std::uint32_t> uint32_values(py::handle obj, std::size_t count, const char* what) {
    const py::array array = entries_for(obj, count, what);
    check_integer_kind(array, what);
    constexpr std::uint64_t largest = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> values(count);
    auto copy = [&](const auto& checked) {
        for (std::size_t i = 0; i < count; ++i) values[i] = static_cast<std::uint32_t>(checked.data()[i]);
    };
    if (array.dtype().kind() == 'u' && array.dtype().itemsize() == 8)
        copy(checked_integers<std::uint64_t>(array, largest, what));
    else
        copy(checked_integers<std::int64_t>(array, largest, what));
    return values;
}

std::vector<std::uint8_t> flag_values(py::handle obj, std::size_t count, const char* what, const char* unit) {
    const py::array array = entries_for(obj, count, what, unit);
    const char kind = array.dtype().kind();
    if (kind != 'b' && kind != 'i' && kind != 'u')
        throw py::type_error(std::string(what) + " must be booleans; got dtype " +
                             py::str(array.dtype()).cast<std::string>());
    const auto set = as_integers<std::uint8_t>(numpy().attr("not_equal")(array, 0));
    return {set.data(), set.data() + set.size()};
}

std::vector<Filter> filter_values(py::handle categories, py::handle masks, std::size_t count) {
    if (categories.is_none() && masks.is_none()) return {};
    std::vector<Filter> filters(count);
    if (!categories.is_none()) {
        const auto values = uint32_values(categories, count, "categories");
        for (std::size_t i = 0; i < count; ++i) filters[i].category = values[i];
    }
    if (!masks.is_none()) {
        const auto values = uint32_values(masks, count, "masks");
        for (std::size_t i = 0; i < count; ++i) filters[i].mask = values[i];
    }
    return filters;
}

#define SMB_PYTHON_INSTANTIATE(Real, Dim)                                       \
    template BoxArray<Real, Dim> box_array<Real, Dim>(py::handle, const char*); \
    template Box<Real, Dim> single_box<Real, Dim>(py::handle, const char*);     \
    template std::array<Real, Dim> coordinates<Real, Dim>(py::handle, const char*);

SMB_PYTHON_INSTANTIATE(float, 2)
SMB_PYTHON_INSTANTIATE(double, 2)
SMB_PYTHON_INSTANTIATE(float, 3)
SMB_PYTHON_INSTANTIATE(double, 3)

#undef SMB_PYTHON_INSTANTIATE

}  // namespace smb::python
