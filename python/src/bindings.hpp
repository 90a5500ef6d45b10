// SPDX-License-Identifier: MIT
#pragma once
// The parts of the module, each in its own translation unit so that they compile side by side.

#include <pybind11/pybind11.h>

#include <atomic>
#include <concepts>
#include <stdexcept>
#include <string>

#include "smb/held_precision.hpp"
#include "smb/profile.hpp"
#include "smb/stats.hpp"

namespace smb::python {

namespace py = pybind11;

/// smb.find_overlapping_pairs over one set and over two (module functions).
void bind_functions(py::module_& module);
/// smb._smb.Detector2f ... Detector3d, wrapped by smb.Detector.
void bind_detectors(py::module_& module);
/// smb._smb.World2f ... World3d, wrapped by smb.World: changes, detection, filters.
void bind_worlds(py::module_& module);
/// The World's queries and ray casts, added to the classes bind_worlds made.
void bind_world_queries(py::module_& module);
/// smb._smb.BoxIndex2f ... BoxIndex3d, wrapped by smb.BoxIndex.
void bind_box_indexes(py::module_& module);
/// smb._smb.PairEvents, wrapped by smb.PairEvents.
void bind_pair_events(py::module_& module);

/// A PairLimitError's message as Python tells it: the library's advice to use its streaming
/// call (which the binding does not offer) replaced by what Python can do.
std::string python_pair_limit_message(const std::string& message);

/// Marks an object as being in a call. Detection runs without the GIL, so a second Python
/// thread could otherwise enter the same World or Detector, which is not synchronised; it gets
/// a RuntimeError instead.
class BusyFlag {
public:
    [[nodiscard]] bool try_enter() noexcept { return !busy_.exchange(true, std::memory_order_acquire); }
    void leave() noexcept { busy_.store(false, std::memory_order_release); }

private:
    std::atomic<bool> busy_{false};
};

/// Holds a BusyFlag for the length of one call.
class BusyScope {
public:
    BusyScope(BusyFlag& flag, const char* what) : flag_(flag) {
        if (!flag_.try_enter())
            throw std::runtime_error(std::string(what) +
                                     " is in use by another thread; one object serves one thread at a time");
    }
    ~BusyScope() { flag_.leave(); }
    BusyScope(const BusyScope&) = delete;
    BusyScope& operator=(const BusyScope&) = delete;

private:
    BusyFlag& flag_;
};

/// A DetectStats as a dict of its fields.
py::dict stats_dict(const DetectStats& stats);
py::dict profile_dict(const DetectProfile& profile);

/// "none", "floats" or "doubles".
const char* precision_name(HeldPrecision precision);

/// The suffix of a class name: "2f", "3d".
template <std::floating_point Real, int Dim>
std::string type_suffix() {
    return std::to_string(Dim) + (sizeof(Real) == sizeof(float) ? "f" : "d");
}

}  // namespace smb::python
