// SPDX-License-Identifier: MIT
#pragma once
// The skin list's fat boxes: a held box grown by the skin, whether a box is still inside its fat
// box, and how much skin the boxes of a detection have left; and the limits past which the skin
// list rebuilds or steps aside.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/held_box.hpp"
#include "core/id_index.hpp"
#include "core/tuning.hpp"
#include "smb/box.hpp"

namespace smb::detail {

// What the skin list knows of each position of its boxes.
inline constexpr std::uint8_t kMoved = 1;  // fat box changed since the rebuild (or new): not in the cells
inline constexpr std::uint8_t kFresh = 2;  // fat box changed in this detection
inline constexpr std::uint8_t kGone = 4;   // its slot is past the caller's array
inline constexpr std::uint8_t kDone = 8;   // fresh, and its new candidates are found already

/// The most candidates the skin list holds for `n` boxes before it steps aside.
[[nodiscard]] inline std::size_t candidate_cap(std::size_t n) noexcept {
    return tuning::skin_candidates_per_box * n + (std::size_t{1} << 20);
}
/// The moved list is tested against every fresh box: past this length a rebuild is cheaper.
[[nodiscard]] inline std::size_t moved_limit(std::size_t n) noexcept {
    return std::max(tuning::moved_limit_floor, n / tuning::moved_limit_divisor);
}

/// Whether the skin list pays for itself. A life: the detections the candidates served between
/// two rebuilds. A rebuild costs more than a detection without a skin, so two short lives running
/// (the motion outruns the skin) and the skin list steps aside.
class CandidateLives {
public:
    /// Counts a detection that rebuilt the candidates, or kept them; true at the end of the second
    /// short life running.
    [[nodiscard]] bool short_again(bool rebuilt) noexcept {
        if (!rebuilt) {
            ++kept_since_rebuild_;
            return false;
        }
        if (kept_since_rebuild_ >= tuning::short_skin_life) {
            short_lives_ = 0;
        } else if (++short_lives_ >= 2) {
            return true;
        }
        kept_since_rebuild_ = 0;
        return false;
    }

private:
    std::size_t kept_since_rebuild_ = tuning::short_skin_life;  // the first build ends no life
    std::size_t short_lives_ = 0;                               // running
};

/// `held` grown by `skin` on every side, rounded outward to floats.
template <int Dim>
[[nodiscard]] Box<float, Dim> fattened(const Box<float, Dim>& held, double skin) noexcept {
    Box<float, Dim> fat;
    for (int k = 0; k < Dim; ++k) {
        fat.min[k] = float_below(static_cast<double>(held.min[k]) - skin);
        fat.max[k] = float_above(static_cast<double>(held.max[k]) + skin);
    }
    return fat;
}

template <int Dim>
[[nodiscard]] bool inside(const Box<float, Dim>& box, const Box<float, Dim>& fat) noexcept {
    // Folded without && (no branch per axis in the skin list's scan, where nearly every box is inside).
    bool in = true;
    for (int k = 0; k < Dim; ++k) {
        in &= fat.min[k] <= box.min[k];
        in &= box.max[k] <= fat.max[k];
    }
    return in;
}

/// The least distance from a held box to a face of its fat box (position p of `held` and `fat`,
/// its slot slot_of[p], those at `n` or past it gone), at most `skin`, on the caller's
/// coordinates. Measured on the held floats, then lowered by their rounding unless they are
/// the input's own (`exact`): a held coordinate is within half a float step of the shifted
/// input (held_box.hpp), at most 2^-24 of the largest held magnitude, so 2^-22 of it covers
/// both boxes' sides.
template <bool exact, int Dim>
[[nodiscard]] double least_skin_left(std::span<const Box<float, Dim>> held, std::span<const Box<float, Dim>> fat,
                                     std::span<const Slot> slot_of, std::size_t n, double skin) noexcept {
    double least = skin;
    double largest = 0;
    for (std::size_t p = 0; p < slot_of.size(); ++p) {
        if (slot_of[p] >= n) continue;
        for (int k = 0; k < Dim; ++k) {
            const double fat_min = fat[p].min[k];
            const double fat_max = fat[p].max[k];
            least = std::min(
                {least, static_cast<double>(held[p].min[k]) - fat_min, fat_max - static_cast<double>(held[p].max[k])});
            largest = std::max({largest, std::abs(fat_min), std::abs(fat_max)});
        }
    }
    if (!exact) least -= std::ldexp(largest, -22) + std::ldexp(1.0, -140);
    return std::max(least, 0.0);
}

}  // namespace smb::detail
