// SPDX-License-Identifier: MIT
#pragma once
// What a Python World holds: the smb::World, the PairEvents its detections feed when asked for,
// and the flag that keeps a second thread out.

#include <memory>
#include <stdexcept>

#include "bindings.hpp"
#include "smb/world.hpp"

namespace smb::python {

template <std::floating_point Real, int Dim>
struct WorldHandle {
    WorldHandle(const WorldSettings& settings, bool with_events, unsigned event_threads) : world(settings) {
        if (with_events) events = std::make_unique<PairEvents>(event_threads);
    }

    PairEvents& checked_events() const {
        if (!events) throw std::runtime_error("pair events are off; construct the World with events=True");
        return *events;
    }

    World<Real, Dim> world;
    std::unique_ptr<PairEvents> events;
    /// Mutable: reads take it too, since a detection in another thread changes what they read.
    mutable BusyFlag busy;
};

template <std::floating_point Real, int Dim>
std::string world_class_name() {
    return "World" + type_suffix<Real, Dim>();
}

}  // namespace smb::python
