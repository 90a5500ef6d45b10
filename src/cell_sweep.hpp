#pragma once
// The cell check of the persistent-cut pipeline: the boxes registered in one cell are copied out
// under local numbers (the global-local map of the paper, here a copy of the boxes themselves so
// that the check reads one small contiguous array), sorted on x by DIS with one increment (the
// list arrives almost sorted: it follows last step's order), and swept on x with direct tests
// on the other axes.
//
// A pair shared by several cells is reported only by the cell that holds the lower corner of the
// two boxes' intersection, p[k] = max(a.min[k], b.min[k]). This replaces the paper's mask array:
// it needs no per-box state, and it stays exact whatever the number of cells a box touches.
// Every box registered in a cell has min[k] < the cell's upper plane on every axis (its min lies
// in the cell's segment or before it), so p lies in the cell iff, on every axis, a.min[k] or
// b.min[k] is at or above the cell's lower plane: one bit per axis and box, computed once.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "box_store.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
struct CellBox {
    std::array<Real, Dim> min;
    std::array<Real, Dim> max;
    Slot slot;
    std::uint32_t inside;  // bit k: min[k] >= the cell's lower plane on axis k
};

/// Lower planes of a cell on every axis (-inf where the cell is first on that axis).
template <std::floating_point Real, int Dim>
using CellFloor = std::array<Real, Dim>;

/// A 32-bit key that never decreases as `value` grows: `value` rounded down to float, with -0
/// made +0 (they are equal coordinates), mapped so that unsigned order is numeric order.
template <std::floating_point Real>
[[nodiscard]] inline std::uint32_t monotone_key(Real value) noexcept {
    const float rounded = static_cast<float>(value) + 0.0F;  // -0 + 0 = +0
    const auto bits = std::bit_cast<std::uint32_t>(rounded);
    std::uint32_t key = (bits & 0x80000000U) != 0 ? ~bits : bits | 0x80000000U;
    if constexpr (!std::is_same_v<Real, float>) {
        // Rounded up: the next key down is the next float down (never below -inf's key).
        key -= static_cast<Real>(rounded) > value ? 1U : 0U;
    }
    return key;
}

template <std::floating_point Real, int Dim>
class CellSweep {
public:
    static constexpr std::uint32_t kAllInside = (1U << Dim) - 1;

    /// Reports every pair of `entries` (positions of the boxes registered in the cell) whose
    /// lower intersection corner lies in the cell, and appends to `home` the positions whose own
    /// lower corner does, in x order: the order the next detection starts from. Returns the
    /// insertion-sort moves.
    template <class Report>
    std::size_t check(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                      std::span<const BoxId> ids, const CellFloor<Real, Dim>& floor, Report& report, std::vector<std::uint32_t>& home) {
        const std::size_t m = entries.size();
        local_.resize(m);
        order_.resize(m);
        CellBox<Real, Dim>* local = local_.data();
        std::uint64_t* order = order_.data();
        for (std::size_t i = 0; i < m; ++i) {
            const std::uint32_t position = entries[i];
            const Box<Real, Dim>& box = boxes[position];
            CellBox<Real, Dim>& out = local[i];
            out.min = box.min;
            out.max = box.max;
            out.slot = position;
            std::uint32_t inside = 0;
            for (int k = 0; k < Dim; ++k) inside |= (box.min[k] >= floor[k] ? 1U : 0U) << k;
            out.inside = inside;
            order[i] = (std::uint64_t{monotone_key(box.min[0])} << 32) | i;
        }
        const std::size_t moves = insertion_sort(order, m);
        order_equal_keys(order, m, ids);
        for (std::size_t i = 0; i < m; ++i) {
            const CellBox<Real, Dim>& a = local[order[i] & 0xFFFFFFFFU];
            if (a.inside == kAllInside) home.push_back(a.slot);
            // Keys never decrease along the order, so once a key passes the key of a.max[0] no
            // later box reaches a on x. Equal keys may hide a slight disorder of the exact
            // values, hence the explicit test of both x ends.
            const std::uint64_t stop = (std::uint64_t{monotone_key(a.max[0])} << 32) | 0xFFFFFFFFU;
            for (std::size_t j = i + 1; j < m && order[j] <= stop; ++j) {
                const CellBox<Real, Dim>& b = local[order[j] & 0xFFFFFFFFU];
                bool hit = (a.inside | b.inside) == kAllInside;
                for (int k = 0; k < Dim; ++k) hit &= (a.min[k] <= b.max[k]) & (b.min[k] <= a.max[k]);
                if (hit) report(a.slot, b.slot);
            }
        }
        return moves;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return local_.capacity() * sizeof(CellBox<Real, Dim>) + order_.capacity() * sizeof(std::uint64_t);
    }

private:
    // Boxes whose keys are equal arrive in an order that depends on the previous step; ordering
    // them by exact coordinate and id makes the reported order a function of the boxes alone,
    // so that detecting twice without changes reports the same list. Such runs are rare outside
    // scenes of equal coordinates, where they are short.
    void order_equal_keys(std::uint64_t* order, std::size_t m, std::span<const BoxId> ids) const {
        const CellBox<Real, Dim>* local = local_.data();
        std::size_t run = 0;
        for (std::size_t i = 1; i <= m; ++i) {
            if (i < m && (order[i] >> 32) == (order[run] >> 32)) continue;
            if (i - run > 1) {
                std::sort(order + run, order + i, [&](std::uint64_t x, std::uint64_t y) {
                    const CellBox<Real, Dim>& a = local[x & 0xFFFFFFFFU];
                    const CellBox<Real, Dim>& b = local[y & 0xFFFFFFFFU];
                    if (a.min[0] != b.min[0]) return a.min[0] < b.min[0];
                    return ids[a.slot] < ids[b.slot];
                });
            }
            run = i;
        }
    }

    // DIS with the single increment 1: the cell's list follows last step's order, so only the
    // boxes that moved past a neighbour, and those registered here from a neighbouring cell,
    // are out of place. The keys carry the local numbers, so a move shifts 8 bytes, not a box.
    static std::size_t insertion_sort(std::uint64_t* keys, std::size_t m) {
        std::size_t moves = 0;
        for (std::size_t i = 1; i < m; ++i) {
            const std::uint64_t moving = keys[i];
            std::size_t j = i;
            while (j > 0 && moving < keys[j - 1]) {
                keys[j] = keys[j - 1];
                --j;
            }
            keys[j] = moving;
            moves += i - j;
        }
        return moves;
    }

    std::vector<CellBox<Real, Dim>> local_;
    std::vector<std::uint64_t> order_;
};

}  // namespace smb::detail
