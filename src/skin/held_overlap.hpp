// SPDX-License-Identifier: MIT
#pragma once
// The skin list's test of a pair of held boxes: whether they overlap, and whether they overlap by
// enough to prove that the input boxes they hold overlap too (held_sure_margin(), held_box.hpp).

#include <cstdint>
#include <cstring>

#include "cuts/float_lanes.hpp"
#include "smb/box.hpp"

namespace smb::detail {

#if defined(__GNUC__)
/// Held boxes `a` and `b` as four lanes of each corner (Dim <= 3): a lane past max[Dim-1] reads
/// the next box or the padding after the last, and the tests mask it off.
template <int Dim>
struct HeldLanes {
    static constexpr std::uint32_t all = (1U << Dim) - 1;
    FloatLanes<4>::Floats a_min, a_max, b_min, b_max;

    [[gnu::always_inline]] HeldLanes(const Box<float, Dim>* a, const Box<float, Dim>* b) noexcept {
        std::memcpy(&a_min, a->min.data(), sizeof a_min);
        std::memcpy(&a_max, a->max.data(), sizeof a_max);
        std::memcpy(&b_min, b->min.data(), sizeof b_min);
        std::memcpy(&b_max, b->max.data(), sizeof b_max);
    }

    /// 1 when every lane of `mask` within Dim is set, else 0. Arithmetic, not a comparison: GCC
    /// turns `== all ? 1 : 0` into a branch in the pass's loop, where half the candidates
    /// overlap and the predictor misses every other one.
    [[nodiscard, gnu::always_inline]] static std::uint32_t every_axis(FloatLanes<4>::Masks mask) noexcept {
        return ((lane_bits<4>(mask) & all) + 1U) >> Dim;
    }
    [[nodiscard, gnu::always_inline]] std::uint32_t hit() const noexcept {
        return every_axis((a_min <= b_max) & (b_min <= a_max));
    }
    [[nodiscard, gnu::always_inline]] std::uint32_t sure(float margin) const noexcept {
        return every_axis(((b_max - a_min) >= margin) & ((a_max - b_min) >= margin));
    }
};
#endif

/// Bit 0: held boxes `a` and `b` overlap; bit 1: they overlap by at least `sure_margin` on
/// every axis, which proves that the input boxes overlap too. Four lanes at a time where GCC's
/// vector extensions are at hand (HeldLanes), so that no branch depends on the answer.
template <int Dim>
[[nodiscard, gnu::always_inline]] inline std::uint32_t overlap_bits(const Box<float, Dim>* a, const Box<float, Dim>* b,
                                                                    float sure_margin) noexcept {
#if defined(__GNUC__)
    if constexpr (Dim <= 3) {
        const HeldLanes<Dim> lanes(a, b);
        return lanes.hit() | (lanes.sure(sure_margin) << 1);
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
/// boxes that are the input's own.
template <int Dim>
[[nodiscard, gnu::always_inline]] inline std::uint32_t overlap_bit(const Box<float, Dim>* a,
                                                                   const Box<float, Dim>* b) noexcept {
#if defined(__GNUC__)
    if constexpr (Dim <= 3) return HeldLanes<Dim>(a, b).hit();
#endif
    return overlap_bits<Dim>(a, b, 0.0F) & 1U;
}

}  // namespace smb::detail
