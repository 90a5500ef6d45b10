// SPDX-License-Identifier: MIT
#pragma once
// The second test of a pair that held floats pass (held_box.hpp): on the caller's own boxes,
// wherever the floats could not prove the overlap. This is what keeps the pairs exact when double
// input is held as floats.

#include <concepts>
#include <cstdint>
#include <span>

#include "core/id_index.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// Whether the input boxes of a pair whose held boxes overlap overlap too. The held boxes are
/// at positions `a` and `b`; slot_at maps a position to the slot of `input` it holds. Held boxes
/// that are the input's own (Held the same type as Input) settle every pair; otherwise `sure`
/// (the floats proved it) settles it, and any other pair is tested on `input`, counted by
/// count_retest().
template <std::floating_point Held, std::floating_point Input, int Dim, class CountRetest>
[[nodiscard]] inline bool confirmed_on_input(std::span<const Box<Input, Dim>> input, std::span<const Slot> slot_at,
                                             std::uint32_t a, std::uint32_t b, bool sure, CountRetest&& count_retest) {
    if constexpr (std::same_as<Held, Input>) {
        (void)input, (void)slot_at, (void)a, (void)b, (void)sure, (void)count_retest;
        return true;
    } else {
        if (sure) return true;
        count_retest();
        return overlaps(input[slot_at[a]], input[slot_at[b]]);
    }
}

}  // namespace smb::detail
