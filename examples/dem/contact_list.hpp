// SPDX-License-Identifier: MIT
#pragma once
// The contacts a DEM step works on, sorted by (a, b), each with its tangential spring: the
// history that lives from the pair's begin event to its end event.

#include <cstdint>
#include <span>
#include <vector>

#include "smb/pair.hpp"
#include "vec3.hpp"

namespace dem {

struct Contact {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    Vec3 spring;  // tangential stretch, zero while the spheres do not touch
};

/// Pairs whose boxes overlap, with their history. Both ways of keeping it are linear merges of
/// sorted lists: with smb's events (begun and ended pairs, sorted by (a, b)), or with the whole
/// sorted pair list of a broad phase that gives no events (the grid).
class ContactList {
public:
    /// Drops the ended pairs and adds the begun ones with a fresh spring.
    void apply_events(std::span<const smb::Pair> ended, std::span<const smb::Pair> begun);
    /// The contacts become `pairs` (sorted by (a, b), each once); pairs that go on keep their spring.
    void assign_sorted(std::span<const smb::Pair> pairs);

    [[nodiscard]] std::span<Contact> contacts() noexcept { return contacts_; }
    [[nodiscard]] std::span<const Contact> contacts() const noexcept { return contacts_; }

private:
    std::vector<Contact> contacts_;
    std::vector<Contact> next_;  // the merge's output, swapped in
};

}  // namespace dem
