// SPDX-License-Identifier: MIT
#pragma once
// Boxes that span more than two segments on some level (the paper's Fig. 5) would be missed by
// the cell check: the middle segment does not hold them. The paper avoids them by never cutting
// finer than twice the largest box; we cut by counts whatever the sizes and check every pair
// that involves such an "oversized" box here instead, by one sweep over the globally sorted
// list of level 0: when a box opens, it is tested against the open oversized boxes, and an
// oversized box that opens is tested against every open box. Each pair involving an oversized
// box is thus tested exactly once (when the later of the two opens), and a floor box under a
// pile of grains costs the grains that touch its slab, not N^2.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "paper/axis_entry.hpp"
#include "smb/box.hpp"

namespace smb::detail {

class OpenSet {
public:
    void reset(std::size_t boxes) {
        position_.assign(boxes, kNone);
        members_.clear();
    }
    void add(std::uint32_t box) {
        position_[box] = static_cast<std::uint32_t>(members_.size());
        members_.push_back(box);
    }
    void remove(std::uint32_t box) {
        const std::uint32_t at = position_[box];
        if (at == kNone) return;
        const std::uint32_t last = members_.back();
        members_[at] = last;
        position_[last] = at;
        members_.pop_back();
        position_[box] = kNone;
    }
    [[nodiscard]] const std::vector<std::uint32_t>& members() const noexcept { return members_; }
    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (position_.capacity() + members_.capacity()) * sizeof(std::uint32_t);
    }

private:
    static constexpr std::uint32_t kNone = ~std::uint32_t{0};
    std::vector<std::uint32_t> position_;
    std::vector<std::uint32_t> members_;
};

template <std::floating_point Real, int Dim>
class OversizedSweep {
public:
    /// `level0` is the sorted list of level 0 (items slot << 1 | end).
    template <class Report>
    void run(std::span<const AxisEntry<Real>> level0, const std::vector<std::uint8_t>& oversized,
             std::span<const Box<Real, Dim>> boxes, Report&& report) {
        open_all_.reset(boxes.size());
        open_oversized_.reset(boxes.size());
        for (const auto& entry : level0) {
            const std::uint32_t slot = entry.item >> 1;
            if (end_of(entry.item) == 1) {
                open_all_.remove(slot);
                if (oversized[slot]) open_oversized_.remove(slot);
                continue;
            }
            const auto& partners = oversized[slot] ? open_all_.members() : open_oversized_.members();
            for (const std::uint32_t other : partners) {
                if (overlaps(boxes[slot], boxes[other])) report(slot, other);
            }
            open_all_.add(slot);
            if (oversized[slot]) open_oversized_.add(slot);
        }
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return open_all_.bytes_held() + open_oversized_.bytes_held();
    }

private:
    OpenSet open_all_;
    OpenSet open_oversized_;
};

}  // namespace smb::detail
