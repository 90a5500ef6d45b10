// SPDX-License-Identifier: MIT
#pragma once
// Bipartite detection: the overlapping pairs between two sets of boxes (particles against a
// mesh, a spatial join of two layers), never the pairs within one set.

#include <concepts>
#include <ranges>
#include <span>
#include <type_traits>
#include <vector>

#include "smb/box.hpp"
#include "smb/pair.hpp"
#include "smb/settings.hpp"

namespace smb {

/// One-shot detection between two static sets of boxes: every pair (a, b) such that box a of
/// `first` and box b of `second` overlap (closed convention, see smb::overlaps). Pair::a is an
/// index into `first`, Pair::b an index into `second`: the two are separate index spaces, so
/// **a < b does not hold here** (a may be larger than b, or equal to it). Each pair appears once;
/// the pairs are returned sorted by (a, b). Pairs within one set are never reported.
///
/// Boxes are validated first: an invalid one throws InvalidBoxError naming its set and index.
/// More than settings.max_pairs_held pairs between the sets throws PairLimitError.
/// `settings` is used as by the one-set overload (cell population, threads, pipeline).
///
/// How: the boxes of both sets that could meet a box of the other one (inside the region where
/// the sets' bounding boxes overlap, and in a cell of a coarse grid that the other set
/// touches) are detected together, and only the pairs with one end in each set are kept.
/// A set much smaller than the other, or lying in a thin layer of it (a floor, the walls of a
/// container), thus spares the detection most of the larger set (docs/two-sets.md).
///
/// For two sets that move from step to step, follow both in one World and tell them apart with
/// collision filters (two categories, each masking out its own): the world then keeps its cuts
/// from one step to the next.
template <std::floating_point Real, int Dim>
[[nodiscard]] std::vector<Pair> find_overlapping_pairs(std::span<const Box<Real, Dim>> first,
                                                       std::span<const Box<Real, Dim>> second,
                                                       const WorldSettings& settings = {});

/// The two-set find_overlapping_pairs over any two BoxRange of the same box type.
template <BoxRange First, BoxRange Second>
requires std::same_as<std::ranges::range_value_t<const First>, std::ranges::range_value_t<const Second>>
[[nodiscard]] std::vector<Pair> find_overlapping_pairs(const First& first, const Second& second,
                                                       const WorldSettings& settings = {}) {
    using box_type = std::ranges::range_value_t<const First>;
    return find_overlapping_pairs<typename box_type::real_type, box_type::dimension>(
        std::span<const box_type>(std::ranges::data(first), std::ranges::size(first)),
        std::span<const box_type>(std::ranges::data(second), std::ranges::size(second)), settings);
}

}  // namespace smb
