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
[[nodiscard, gnu::always_inline]] inline std::uint32_t overlap_bits(const Box<float, Dim>* a, const Box<float, Dim>* b,
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
        // Arithmetic, as in overlap_bit(): no branch on the answer.
        const std::uint32_t hit_bit = ((lane_bits<4>(hit) & all) + 1U) >> Dim;
        const std::uint32_t sure_bit = ((lane_bits<4>(sure) & all) + 1U) >> Dim;
        return hit_bit | (sure_bit << 1);
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
    return ((hit_bits + 1U) >> Dim) | (((sure_bits + 1U) >> Dim) << 1);
}

/// 1 when held boxes `a` and `b` overlap, else 0: overlap_bits() without the sure bit, for held
/// boxes that are the input's own. The same four lanes and padding.
template <int Dim>
[[nodiscard, gnu::always_inline]] inline std::uint32_t overlap_bit(const Box<float, Dim>* a,
                                                                   const Box<float, Dim>* b) noexcept {
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
        // Arithmetic, not a comparison: GCC turns `== all ? 1 : 0` into a branch in the pass's
        // loop, where half the candidates overlap and the predictor misses every other one.
        return ((lane_bits<4>(hit) & all) + 1U) >> Dim;
    }
#endif
    std::uint32_t hit_bits = 0;
    for (int k = 0; k < Dim; ++k) {
        const bool hit = a->min[k] <= b->max[k] && b->min[k] <= a->max[k];
        hit_bits |= static_cast<std::uint32_t>(hit) << k;
    }
    return (hit_bits + 1U) >> Dim;
}

}  // namespace smb::detail
