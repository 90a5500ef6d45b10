// SPDX-License-Identifier: MIT
#pragma once
// Steps 9-11 of the paper's Section 3 (its expressions (10) and (11)): an upper list, sorted on
// its own axis, is regrouped by cell. Each corner lies in exactly one cell (`cell_of`, the
// index array: the deepest level's segment of the corner); scanning the upper list in its
// sorted order and appending every corner to its cell's part leaves each part sorted, in linear
// time, without sorting anything again.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "paper/axial_cut.hpp"
#include "paper/axis_entry.hpp"

namespace smb::detail {

/// `upper_items` are the items of an upper list in its order; each stands for
/// 2^`corners_shift` consecutive corner ids (item << shift ...). `cell_begin` (cells + 1
/// offsets) says where each cell's part starts in `out`.
template <class ItemRange>
void regroup_by_cell(const ItemRange& upper_items, int corners_shift, std::span<const SegmentId> cell_of,
                     std::span<const std::uint32_t> cell_begin, std::vector<Item>& out,
                     std::vector<std::uint32_t>& cursor) {
    const std::size_t cells = cell_begin.size() - 1;
    out.resize(cell_begin[cells]);
    cursor.assign(cell_begin.begin(), cell_begin.begin() + static_cast<std::ptrdiff_t>(cells));
    const Item corners = Item{1} << corners_shift;
    for (const Item item : upper_items) {
        const Item first = item << corners_shift;
        for (Item corner = first; corner < first + corners; ++corner) {
            out[cursor[cell_of[corner]]++] = corner;
        }
    }
}

/// A view of a list's item ids, for regroup_by_cell (std::views::transform would do, but clang 14
/// cannot compile libstdc++ 12's, and the fuzzers are built with clang).
template <std::floating_point Real>
class ItemsOf {
public:
    explicit ItemsOf(std::span<const AxisEntry<Real>> list) : list_(list) {}
    class iterator {
    public:
        explicit iterator(const AxisEntry<Real>* at) : at_(at) {}
        Item operator*() const noexcept { return at_->item; }
        iterator& operator++() noexcept {
            ++at_;
            return *this;
        }
        bool operator!=(const iterator& other) const noexcept { return at_ != other.at_; }

    private:
        const AxisEntry<Real>* at_;
    };
    [[nodiscard]] iterator begin() const noexcept { return iterator(list_.data()); }
    [[nodiscard]] iterator end() const noexcept { return iterator(list_.data() + list_.size()); }

private:
    std::span<const AxisEntry<Real>> list_;
};

}  // namespace smb::detail
