// SPDX-License-Identifier: MIT
#pragma once
// The check every Detector input passes, and what the Detector learns from it: the bounds of the
// scene, and whether floats shifted to its middle resolve its boxes.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>

#include "core/invalid_box.hpp"
#include "cuts/float_lanes.hpp"
#include "smb/box.hpp"
#include "smb/errors.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
struct SceneBounds {
    std::array<Real, Dim> lo{};
    std::array<Real, Dim> hi{};

    [[nodiscard]] bool within(const SceneBounds& region) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            if (lo[k] < region.lo[k] || hi[k] > region.hi[k]) return false;
        }
        return true;
    }
};

#if defined(__GNUC__)
/// Float boxes of 2 or 3 axes: the scan of checked_bounds() four lanes at a time, two boxes an
/// iteration into two sets of lanes, so that the minimum and maximum of one box need not wait
/// for those of the box before (the scalar loop is bound by that chain). A box is read as `low`,
/// the 16 bytes from its min, and `high`, the 16 bytes that end with its max: both inside the box.
/// Lane k of `low` holds min[k], lane k + 4 - Dim of `high` holds max[k]. Returns the bounds and
/// whether every min was at most its max.
template <int Dim>
requires(Dim == 2 || Dim == 3) [[nodiscard]] bool scan_float_lanes(std::span<const Box<float, Dim>> boxes,
                                                                   SceneBounds<float, Dim>& bounds) noexcept {
    using Floats = FloatLanes<4>::Floats;
    using Masks = FloatLanes<4>::Masks;
    constexpr int shift = 4 - Dim;  // the lane of max[0] in `high`
    constexpr std::size_t high_offset = sizeof(Box<float, Dim>) - sizeof(Floats);
    constexpr float inf = std::numeric_limits<float>::infinity();
    Floats low_min[2] = {{inf, inf, inf, inf}, {inf, inf, inf, inf}};
    Floats high_max[2] = {{-inf, -inf, -inf, -inf}, {-inf, -inf, -inf, -inf}};
    Masks ordered = {-1, -1, -1, -1};
    const auto* bytes = reinterpret_cast<const unsigned char*>(boxes.data());
    auto take = [&](std::size_t i, int set) {
        Floats low;
        Floats high;
        std::memcpy(&low, bytes + i * sizeof(Box<float, Dim>), sizeof low);
        std::memcpy(&high, bytes + i * sizeof(Box<float, Dim>) + high_offset, sizeof high);
        low_min[set] = low < low_min[set] ? low : low_min[set];
        high_max[set] = high > high_max[set] ? high : high_max[set];
        const Floats max_at_min_lanes = {high[shift], high[shift + 1], high[3], high[3]};
        ordered &= low <= max_at_min_lanes;
    };
    std::size_t i = 0;
    for (; i + 2 <= boxes.size(); i += 2) {
        take(i, 0);
        take(i + 1, 1);
    }
    if (i < boxes.size()) take(i, 0);
    bool valid = true;
    for (int k = 0; k < Dim; ++k) {
        bounds.lo[k] = std::min(low_min[0][k], low_min[1][k]);
        bounds.hi[k] = std::max(high_max[0][k + shift], high_max[1][k + shift]);
        valid &= ordered[k] != 0;
    }
    return valid;
}
#endif

/// The bounds of `boxes` (not empty), or InvalidBoxError naming the first invalid box. One
/// branch-free pass in the common case: the comparisons are folded into one flag, and the
/// offender is looked for only when the flag says there is one.
template <std::floating_point Real, int Dim>
[[nodiscard]] SceneBounds<Real, Dim> checked_bounds(std::span<const Box<Real, Dim>> boxes) {
    SceneBounds<Real, Dim> bounds;
    bool valid = true;
#if defined(__GNUC__)
    if constexpr (std::same_as<Real, float> && (Dim == 2 || Dim == 3)) {
        valid = scan_float_lanes<Dim>(boxes, bounds);
    } else
#endif
    {
        bounds.lo.fill(std::numeric_limits<Real>::infinity());
        bounds.hi.fill(-std::numeric_limits<Real>::infinity());
        for (const Box<Real, Dim>& box : boxes) {
            for (int k = 0; k < Dim; ++k) {
                // NaN fails min <= max; an infinity shows in the bounds (checked below).
                valid &= box.min[k] <= box.max[k];
                bounds.lo[k] = std::min(bounds.lo[k], box.min[k]);
                bounds.hi[k] = std::max(bounds.hi[k], box.max[k]);
            }
        }
    }
    for (int k = 0; k < Dim; ++k) valid &= std::isfinite(bounds.lo[k]) && std::isfinite(bounds.hi[k]);
    if (!valid) {
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (!is_valid(boxes[i])) throw InvalidBoxError(describe_invalid_box(static_cast<BoxId>(i), boxes[i]));
        }
    }
    return bounds;
}

/// Whether a Detector of double boxes may hold them as floats shifted to the middle of
/// `bounds`, and the region that choice holds for: the bounds grown by half their extent on
/// every side, so that a scene that drifts is not re-judged at every step.
template <std::floating_point Real, int Dim>
struct FloatResolution {
    bool floats = false;
    std::array<Real, Dim> origin{};
    SceneBounds<Real, Dim> region;
};

/// Floats hold a box to about 2^-24 of the scene's extent. A box thinner than 2^-14 of that
/// extent on some axis would grow by more than a 1/1024 of its width, and a crowd of them would
/// turn into a crowd of false candidates: when more than 1/8 of the boxes are that thin, or the
/// scene goes beyond the float range, the detector holds doubles.
template <std::floating_point Real, int Dim>
[[nodiscard]] FloatResolution<Real, Dim> judge_float_resolution(std::span<const Box<Real, Dim>> boxes,
                                                                const SceneBounds<Real, Dim>& bounds) {
    FloatResolution<Real, Dim> judged;
    std::array<Real, Dim> thin{};
    constexpr Real kLargest = static_cast<Real>(std::numeric_limits<float>::max()) / 8;
    for (int k = 0; k < Dim; ++k) {
        const Real extent = bounds.hi[k] - bounds.lo[k];
        if (!(extent < kLargest) || std::abs(bounds.lo[k]) > kLargest || std::abs(bounds.hi[k]) > kLargest)
            return judged;
        thin[k] = std::ldexp(extent, -14);
        judged.origin[k] = bounds.lo[k] / 2 + bounds.hi[k] / 2;
        judged.region.lo[k] = bounds.lo[k] - extent / 2;
        judged.region.hi[k] = bounds.hi[k] + extent / 2;
    }
    std::size_t thin_boxes = 0;
    for (const Box<Real, Dim>& box : boxes) {
        bool is_thin = false;
        for (int k = 0; k < Dim; ++k) is_thin |= box.max[k] - box.min[k] < thin[k];
        thin_boxes += is_thin ? 1U : 0U;
    }
    judged.floats = 8 * thin_boxes <= boxes.size();
    return judged;
}

}  // namespace smb::detail
