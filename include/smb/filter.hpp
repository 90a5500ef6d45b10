// SPDX-License-Identifier: MIT
#pragma once
// Which pairs a World or Detector reports: category and mask bits per box, as Box2D and Bullet
// have them, an optional predicate for what bits cannot say, and static boxes.

#include <cstdint>
#include <functional>
#include <span>

#include "smb/pair.hpp"

namespace smb {

/// The collision filter of one box. Boxes a and b are paired when they overlap and
/// (a.category & b.mask) != 0 and (b.category & a.mask) != 0. The defaults (category 1, every
/// mask bit) filter nothing. A box whose category or mask is 0 pairs with nothing, and a World
/// keeps it out of its detection altogether.
struct Filter {
    std::uint32_t category = 1;
    std::uint32_t mask = ~std::uint32_t{0};

    friend bool operator==(const Filter&, const Filter&) = default;
};

/// True when the bits let a and b pair (the test is symmetric).
[[nodiscard]] constexpr bool filters_pass(const Filter& a, const Filter& b) noexcept {
    return (a.category & b.mask) != 0 && (b.category & a.mask) != 0;
}

/// True when a box with this filter can pair with some box.
[[nodiscard]] constexpr bool filter_interacts(const Filter& f) noexcept { return f.category != 0 && f.mask != 0; }

/// Says whether two overlapping boxes whose filters pass are reported: called with (a, b),
/// a < b (ids in a World, indices in a Detector), only for pairs that overlap and pass the
/// bits, from the thread that called detect(). It must not change the World or Detector.
using PairPredicate = std::function<bool(BoxId, BoxId)>;

/// What a Detector is told about the boxes of one call, beside the boxes: each span is either
/// empty (every box has the default) or holds one entry per box.
struct DetectFilters {
    /// Filter of box i.
    std::span<const Filter> filters;
    /// Non-zero: box i is static, and two static boxes are never paired.
    std::span<const std::uint8_t> statics;
    /// Empty: none.
    PairPredicate predicate;
};

}  // namespace smb
