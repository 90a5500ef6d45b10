// SPDX-License-Identifier: MIT
#include "arrays.hpp"

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

/// `array` as C-contiguous Real: itself when it is already that, else a converted copy. A dtype
/// that NumPy casts to Real without loss is converted; any other integer or float dtype only
/// when every value survives the conversion (so the boxes detected are the caller's boxes).
template <std::floating_point Real>
py::array as_real(const py::array& array, const char* what) {
    const py::dtype wanted = py::dtype::of<Real>();
    if (!array.dtype().equal(wanted)) {
        const char kind = array.dtype().kind();
        if (kind != 'f' && kind != 'i' && kind != 'u')
            throw py::type_error(std::string(what) + " must hold numbers (" + dtype_name<Real>() + "); got dtype " +
                                 py::str(array.dtype()).cast<std::string>());
        const bool lossless = numpy().attr("can_cast")(array.dtype(), wanted, "safe").cast<bool>();
        if (!lossless) {
            const py::object converted = array.attr("astype")(wanted);
            const py::object back = converted.attr("astype")(array.dtype());
            const py::object same = numpy().attr("array_equal")(back, array, py::arg("equal_nan") = true);
            if (!py::cast<bool>(same))
                throw py::type_error(std::string(what) + ": the " + py::str(array.dtype()).cast<std::string>() +
                                     " values do not all convert exactly to " + dtype_name<Real>() +
                                     ", the dtype expected here; convert them first (.astype(numpy." +
                                     dtype_name<Real>() + ")) to accept the rounding");
        }
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

/// `obj` as a 1-D integer array of `count` entries (a single value stands for all), checked to
/// lie in [0, limit]; returned as int64 or, for uint64 input, uint64.
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
py::array entries_for(py::handle obj, std::size_t count, const char* what) {
    py::array array = as_array(obj);
    if (array.ndim() == 0) return numpy().attr("full")(count, array);
    if (array.ndim() != 1)
        throw py::value_error(std::string(what) + " must be one value or 1-D; got shape " + shape_text(array));
    check_count(static_cast<std::size_t>(array.shape(0)), count, what);
    return array;
}

void check_integer_kind(const py::array& array, const char* what) {
    const char kind = array.dtype().kind();
    if (kind != 'i' && kind != 'u' && !(kind == 'b' && array.size() == 0) && !(kind == 'f' && array.size() == 0))
        throw py::type_error(std::string(what) + " must be integers; got dtype " +
                             py::str(array.dtype()).cast<std::string>());
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

void check_count(std::size_t got, std::size_t expected, const char* what) {
    if (got != expected)
        throw py::value_error(std::string(what) + " has " + std::to_string(got) + " entries; " +
                              std::to_string(expected) + " expected (one per box)");
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
    const py::array held = as_real<Real>(array, what);
    std::array<Real, Dim> values;
    std::memcpy(values.data(), held.data(), sizeof values);
    return values;
}

IdArray id_array(py::handle obj, const char* what) {
    py::array array = as_array(obj);
    if (array.ndim() == 0) array = array.attr("reshape")(1);
    if (array.ndim() != 1) throw py::value_error(std::string(what) + " must be 1-D; got shape " + shape_text(array));
    check_integer_kind(array, what);
    constexpr auto largest = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    py::array held;
    if (array.dtype().kind() == 'u' && array.dtype().itemsize() == 8)
        held = checked_integers<std::uint64_t>(array, largest, what);
    else
        held = checked_integers<std::int64_t>(array, largest, what);
    static_assert(sizeof(BoxId) == sizeof(std::int64_t));
    return {held,
            std::span<const BoxId>(static_cast<const BoxId*>(held.data()), static_cast<std::size_t>(held.size()))};
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

std::vector<std::uint8_t> flag_values(py::handle obj, std::size_t count, const char* what) {
    const py::array array = entries_for(obj, count, what);
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

py::array_t<std::int64_t> pair_array(std::vector<Pair>&& pairs) {
    static_assert(sizeof(Pair) == 2 * sizeof(std::int64_t), "a pair must be two ids to be handed over in place");
    auto* held = new std::vector<Pair>(std::move(pairs));
    const py::capsule keep_alive(held, [](void* p) { delete static_cast<std::vector<Pair>*>(p); });
    const auto count = static_cast<py::ssize_t>(held->size());
    const auto* first = reinterpret_cast<const std::int64_t*>(held->data());
    return py::array_t<std::int64_t>({count, py::ssize_t{2}}, {py::ssize_t{sizeof(Pair)}, py::ssize_t{8}}, first,
                                     keep_alive);
}

py::array_t<std::int64_t> pair_array_copy(std::span<const Pair> pairs) {
    py::array_t<std::int64_t> array({static_cast<py::ssize_t>(pairs.size()), py::ssize_t{2}});
    if (!pairs.empty()) std::memcpy(array.mutable_data(), pairs.data(), pairs.size_bytes());
    return array;
}

py::array_t<std::int64_t> id_result(std::vector<BoxId>&& ids) {
    auto* held = new std::vector<BoxId>(std::move(ids));
    const py::capsule keep_alive(held, [](void* p) { delete static_cast<std::vector<BoxId>*>(p); });
    return py::array_t<std::int64_t>({static_cast<py::ssize_t>(held->size())}, {py::ssize_t{8}},
                                     reinterpret_cast<const std::int64_t*>(held->data()), keep_alive);
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
