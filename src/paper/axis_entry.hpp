// SPDX-License-Identifier: MIT
#pragma once
// An item of a persistent SMB list: the id of a projection (the paper's vertex numbers) with
// its coordinate kept beside it (refreshed from the boxes once per step), so that sorting
// compares contiguous keys instead of chasing ids into the box array.

#include <concepts>
#include <cstdint>

namespace smb::detail {

/// Item ids of level l are slot << (l + 1) | the end bits of levels 0..l: bit 0 of the id is the
/// end (0 = min, 1 = max) on this level's axis, and id >> 1 is the parent item on the level
/// above. The deepest level's items are the paper's box corners.
using Item = std::uint32_t;

// Packed to 4-byte alignment: with double keys an entry is 12 bytes instead of 16, a quarter of
// the lists' memory; x86 and ARMv8 load an unaligned double at the speed of an aligned one.
#pragma pack(push, 4)
template <std::floating_point Real>
struct AxisEntry {
    Real key;
    Item item;
};
#pragma pack(pop)
static_assert(sizeof(AxisEntry<double>) == 12 && sizeof(AxisEntry<float>) == 8);

/// Total order of a list: by coordinate; at equal coordinates a min end before a max end, so
/// that touching intervals (closed convention) are seen as overlapping by every sweep and no
/// cut can separate them; remaining ties by item id, so that sorting is deterministic.
template <std::floating_point Real>
[[nodiscard]] inline bool entry_less(const AxisEntry<Real>& a, const AxisEntry<Real>& b) noexcept {
    if (a.key < b.key) return true;
    if (b.key < a.key) return false;
    const Item end_a = a.item & 1U;
    const Item end_b = b.item & 1U;
    if (end_a != end_b) return end_a < end_b;
    return a.item < b.item;
}

/// entry_less as a function object: standard algorithms inline a functor's call, while a
/// function pointer costs a call per comparison.
struct EntryLess {
    template <std::floating_point Real>
    bool operator()(const AxisEntry<Real>& a, const AxisEntry<Real>& b) const noexcept {
        return entry_less(a, b);
    }
};

[[nodiscard]] constexpr Item end_of(Item item) noexcept { return item & 1U; }

}  // namespace smb::detail
