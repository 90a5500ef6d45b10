// SPDX-License-Identifier: MIT
#pragma once
// The skin list's test of a pair of held boxes: whether they overlap, and whether they overlap by
// enough to prove that the input boxes they hold overlap too (held_sure_margin(), held_box.hpp).

#include <cstdint>
#include <cstring>

#include "cuts/float_lanes.hpp"
#include "smb/box.hpp"

namespace smb::detail {

/// Bit 0: held boxes `a` and `b` overlap; bit 1: they overlap by at least `sure_margin` on
/// every axis, which proves that the input boxes overlap too. Four lanes at a time where GCC's
/// vector extensions are at hand (a lane past max[Dim-1] reads the next box or the padding after
/// the last, and is masked off), so that no branch depends on the answer.
template <int Dim>
[[nodiscard]] inline std::uint32_t overlap_bits(const Box<float, Dim>* a, const Box<float, Dim>* b,
                                                float sure_margin) noexcept {
    constexpr std::uint32_t all = (1U << Dim) - 1;
#if defined(__GNUC__)
    if constexpr (Dim <= 3) {
        using Lanes = FloatLanes<4>::Floats;
        Lanes a_min, a_max, b_min, b_max;
        std::memcpy(&a_min, a->min.data(), sizeof a_min);
        std::memcpy(&a_max, a->max.data(), sizeof a_max);
        std::memcpy(&b_min, b->min.data(), sizeof b_min);
        std::memcpy(&b_max, b->max.data(), sizeof b_max);
        const FloatLanes<4>::Masks hit = (a_min <= b_max) & (b_min <= a_max);
        const FloatLanes<4>::Masks sure = ((b_max - a_min) >= sure_margin) & ((a_max - b_min) >= sure_margin);
        const std::uint32_t hit_bits = lane_bits<4>(hit) & all;
        const std::uint32_t sure_bits = lane_bits<4>(sure) & all;
        return (hit_bits == all ? 1U : 0U) | (sure_bits == all ? 2U : 0U);
    }
#endif
    std::uint32_t hit_bits = 0;
    std::uint32_t sure_bits = 0;
    for (int k = 0; k < Dim; ++k) {
        const bool hit = a->min[k] <= b->max[k] && b->min[k] <= a->max[k];
        const bool sure = b->max[k] - a->min[k] >= sure_margin && a->max[k] - b->min[k] >= sure_margin;
        hit_bits |= static_cast<std::uint32_t>(hit) << k;
        sure_bits |= static_cast<std::uint32_t>(sure) << k;
    }
    return (hit_bits == all ? 1U : 0U) | (sure_bits == all ? 2U : 0U);
}

}  // namespace smb::detail
