// SPDX-License-Identifier: MIT
// Ids into the binding (the whole 64-bit range) and pairs and ids out of it, as NumPy arrays.

#include <climits>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include "arrays.hpp"

namespace smb::python {

namespace {

const char* const id_range = "[0, 2**64 - 1]";

std::string repr_text(py::handle obj) { return py::repr(obj).cast<std::string>(); }

/// `obj` as an id, or nothing; `problem` tells why not ("negative", "too large", "not an
/// integer") for the caller's message.
std::optional<BoxId> read_id(py::handle obj, const char*& problem) {
    // operator.index: Python and NumPy integers (and bool), never a float or a string.
    PyObject* index = PyNumber_Index(obj.ptr());
    if (index == nullptr) {
        PyErr_Clear();
        problem = "not an integer";
        return std::nullopt;
    }
    const auto integer = py::reinterpret_steal<py::int_>(index);
    int overflow = 0;
    const long long small = PyLong_AsLongLongAndOverflow(integer.ptr(), &overflow);
    if (overflow < 0 || (overflow == 0 && small < 0)) {
        problem = "negative";
        return std::nullopt;
    }
    if (overflow == 0) return static_cast<BoxId>(small);
    const unsigned long long large = PyLong_AsUnsignedLongLong(integer.ptr());
    if (large == static_cast<unsigned long long>(-1) && PyErr_Occurred() != nullptr) {
        PyErr_Clear();
        problem = "too large";
        return std::nullopt;
    }
    static_assert(sizeof(unsigned long long) == sizeof(BoxId));
    return static_cast<BoxId>(large);
}

/// An object array (Python integers beyond int64, or mixed with negative ones) read one by one.
py::array ids_from_objects(const py::array& array, const char* what) {
    py::array_t<BoxId> ids(array.size());
    BoxId* out = ids.mutable_data();
    py::ssize_t i = 0;
    for (const py::handle item : array.attr("flat")) {
        const char* problem = "";
        const std::optional<BoxId> id = read_id(item, problem);
        if (!id) {
            const std::string text = std::string(what) + ": entry " + std::to_string(i) + " is " + repr_text(item) +
                                     ", " + problem + "; ids are integers in " + id_range;
            if (std::string(problem) == "not an integer") throw py::type_error(text);
            throw py::value_error(text);
        }
        out[i++] = *id;
    }
    return ids;
}

}  // namespace

py::array as_id_array(py::handle obj) {
    py::array array = as_array(obj);
    // NumPy makes float64 of a list that mixes integers at or above 2^63 with others (uint64
    // and int64 promote to float64), which would round the ids: such a list is read one by one.
    if (array.dtype().kind() == 'f' && array.size() > 0 && !py::isinstance<py::array>(obj))
        array = py::module_::import("numpy").attr("asarray")(obj, py::arg("dtype") = "object");
    return array;
}

IdArray id_array(py::handle obj, const char* what) {
    py::array array = as_id_array(obj);
    if (array.ndim() == 0) array = array.attr("reshape")(1);
    if (array.ndim() != 1) throw py::value_error(std::string(what) + " must be 1-D; got shape " + shape_text(array));
    const char kind = array.dtype().kind();
    py::array held;
    if (kind == 'u') {
        held = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>(array);
    } else if (kind == 'i') {
        const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>(array);
        const std::int64_t* data = values.data();
        for (py::ssize_t i = 0; i < values.size(); ++i)
            if (data[i] < 0)
                throw py::value_error(std::string(what) + " must not be negative; entry " + std::to_string(i) + " is " +
                                      std::to_string(data[i]) + " (ids are integers in " + id_range + ")");
        held = values;  // the same bits as uint64, every value being non-negative
    } else if (kind == 'O') {
        held = ids_from_objects(array, what);
    } else if (array.size() == 0) {
        held = py::array_t<std::uint64_t>(0);  // [] is float64 to NumPy
    } else {
        throw py::type_error(std::string(what) + " must be integers in " + id_range + "; got dtype " +
                             py::str(array.dtype()).cast<std::string>());
    }
    static_assert(sizeof(BoxId) == sizeof(std::int64_t));
    return {held,
            std::span<const BoxId>(static_cast<const BoxId*>(held.data()), static_cast<std::size_t>(held.size()))};
}

BoxId single_id(py::handle obj, const char* what) {
    const char* problem = "";
    const std::optional<BoxId> id = read_id(obj, problem);
    if (id) return *id;
    const std::string text =
        std::string(what) + " must be an integer in " + id_range + "; got " + repr_text(obj) + " (" + problem + ")";
    if (std::string(problem) == "not an integer") throw py::type_error(text);
    throw py::value_error(text);
}

std::optional<BoxId> id_if_valid(py::handle obj) {
    const char* problem = "";
    return read_id(obj, problem);
}

template <OutputId Id>
py::array_t<Id> pair_array(std::vector<Pair>&& pairs) {
    static_assert(sizeof(Pair) == 2 * sizeof(Id), "a pair must be two ids to be handed over in place");
    auto* held = new std::vector<Pair>(std::move(pairs));
    const py::capsule keep_alive(held, [](void* p) { delete static_cast<std::vector<Pair>*>(p); });
    const auto count = static_cast<py::ssize_t>(held->size());
    const auto* first = reinterpret_cast<const Id*>(held->data());
    return py::array_t<Id>({count, py::ssize_t{2}}, {py::ssize_t{sizeof(Pair)}, py::ssize_t{sizeof(Id)}}, first,
                           keep_alive);
}

template <OutputId Id>
py::array_t<Id> pair_array_copy(std::span<const Pair> pairs) {
    py::array_t<Id> array({static_cast<py::ssize_t>(pairs.size()), py::ssize_t{2}});
    if (!pairs.empty()) std::memcpy(array.mutable_data(), pairs.data(), pairs.size_bytes());
    return array;
}

template <OutputId Id>
py::array_t<Id> id_result(std::vector<BoxId>&& ids) {
    auto* held = new std::vector<BoxId>(std::move(ids));
    const py::capsule keep_alive(held, [](void* p) { delete static_cast<std::vector<BoxId>*>(p); });
    return py::array_t<Id>({static_cast<py::ssize_t>(held->size())}, {py::ssize_t{sizeof(Id)}},
                           reinterpret_cast<const Id*>(held->data()), keep_alive);
}

template <OutputId Id>
py::array pair_buffer_array(py::handle out) {
    const char* const dtype = std::is_same_v<Id, std::int64_t> ? "int64" : "uint64";
    if (!py::isinstance<py::array>(out))
        throw py::type_error(std::string("out must be a NumPy array of shape (M, 2) and dtype ") + dtype + "; got " +
                             py::str(py::type::handle_of(out)).cast<std::string>());
    const auto array = py::reinterpret_borrow<py::array>(out);
    if (!array.dtype().equal(py::dtype::of<Id>()))
        throw py::type_error(std::string("out must have dtype ") + dtype + ", the dtype of the pairs; got " +
                             py::str(array.dtype()).cast<std::string>());
    if (array.ndim() != 2 || array.shape(1) != 2)
        throw py::value_error("out must have shape (M, 2); got shape " + shape_text(array));
    if ((array.flags() & py::array::c_style) == 0)
        throw py::value_error("out must be C-contiguous (numpy.empty((M, 2), ...) is)");
    if (!array.writeable()) throw py::value_error("out must be writeable");
    return array;
}

template <OutputId Id>
py::array pairs_into(py::array out, std::span<const Pair> pairs) {
    if (pairs.size() > static_cast<std::size_t>(out.shape(0))) return pair_array_copy<Id>(pairs);
    if (!pairs.empty()) std::memcpy(out.mutable_data(), pairs.data(), pairs.size_bytes());
    const py::object rows = out[py::slice(0, static_cast<py::ssize_t>(pairs.size()), 1)];
    return py::reinterpret_borrow<py::array>(rows);
}

#define SMB_PYTHON_INSTANTIATE(Id)                                       \
    template py::array_t<Id> pair_array<Id>(std::vector<Pair> &&);       \
    template py::array_t<Id> pair_array_copy<Id>(std::span<const Pair>); \
    template py::array_t<Id> id_result<Id>(std::vector<BoxId> &&);       \
    template py::array pair_buffer_array<Id>(py::handle);                \
    template py::array pairs_into<Id>(py::array, std::span<const Pair>);

SMB_PYTHON_INSTANTIATE(std::int64_t)
SMB_PYTHON_INSTANTIATE(std::uint64_t)

#undef SMB_PYTHON_INSTANTIATE

}  // namespace smb::python
