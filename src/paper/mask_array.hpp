// SPDX-License-Identifier: MIT
#pragma once
// The mask array of the paper's Section 2.4 (8), expression (13): one byte per box, one bit per
// level of cut. Cells are checked in order (slab, column, cell). Bit l of a box is set once the
// box has been in a finished segment of level l that encloses the current one's predecessor:
//   - after a cell (deepest level) is checked, its boxes get the deepest bit;
//   - after a segment of level l < deepest is finished, its boxes lose bit l + 1 and get bit l.
// Two boxes that share a bit were both present in the previous segment of that level. Since a
// box that is not oversized spans at most two consecutive segments on every level, both were
// then present in one earlier cell together whenever they overlap, and the pair was reported
// there: skipping it now reports every contact exactly once (docs/algorithm.md has the proof).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace smb::detail {

class MaskArray {
public:
    void reset(std::size_t boxes) { bits_.assign(boxes, 0); }

    /// True when the two boxes were already checked together in an earlier cell.
    [[nodiscard]] bool already_checked(std::uint32_t a, std::uint32_t b) const noexcept {
        return (bits_[a] & bits_[b]) != 0;
    }

    void mark_cell_done(std::uint32_t box, int deepest_level) noexcept {
        bits_[box] = static_cast<std::uint8_t>(bits_[box] | (1U << deepest_level));
    }

    /// A segment of `level` is finished: `box` was in it.
    void mark_segment_done(std::uint32_t box, int level) noexcept {
        const unsigned cleared = bits_[box] & ~(1U << (level + 1));
        bits_[box] = static_cast<std::uint8_t>(cleared | (1U << level));
    }

    [[nodiscard]] std::uint8_t bits(std::uint32_t box) const noexcept { return bits_[box]; }
    [[nodiscard]] std::size_t bytes_held() const noexcept { return bits_.capacity(); }

private:
    std::vector<std::uint8_t> bits_;
};

}  // namespace smb::detail
