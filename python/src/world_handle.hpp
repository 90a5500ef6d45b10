// SPDX-License-Identifier: MIT
#pragma once
// What a Python World holds: the smb::World, the PairEvents its detections feed when asked for,
// and the flag that keeps a second thread out.

#include <memory>
#include <stdexcept>
#include <vector>

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

    /// A vector for the next detection's pairs, with room for as many as the last one found and
    /// an eighth more. Each detection hands its vector over to the array it returns, so the
    /// next one starts empty; grown by doubling, it would copy its pairs and fault in fresh pages
    /// about twice over (at 2 million pairs that tripled the call beside the C++ one).
    [[nodiscard]] std::vector<Pair> pair_buffer() const {
        std::vector<Pair> pairs;
        pairs.reserve(last_pair_count + last_pair_count / 8);
        return pairs;
    }

    World<Real, Dim> world;
    std::unique_ptr<PairEvents> events;
    std::size_t last_pair_count = 0;
    /// The pairs of the detections that write into the caller's buffer (out=): kept from call
    /// to call, so that its pages stay mapped, as a C++ caller's reused vector.
    std::vector<Pair> reused;
    /// Mutable: reads take it too, since a detection in another thread changes what they read.
    mutable BusyFlag busy;
};

template <std::floating_point Real, int Dim>
std::string world_class_name() {
    return "World" + type_suffix<Real, Dim>();
}

}  // namespace smb::python
