// SPDX-License-Identifier: MIT
#pragma once
// The static boxes of a World, copied once into the one grid of smb (query/grid_index.hpp, where
// a floor under a pile of grains sits on a coarse level of its own). It is built when the statics
// change and read by every moving box that left its fat box (static_contacts.hpp). Positions are
// the grid's: the statics' ids and filters are kept in the grid's order beside its boxes.

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/tuning.hpp"
#include "query/grid_index.hpp"
#include "smb/box.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class StaticGrid {
public:
    [[nodiscard]] std::size_t size() const noexcept { return grid_.boxes.size(); }
    [[nodiscard]] bool empty() const noexcept { return grid_.boxes.empty(); }
    [[nodiscard]] const Box<Real, Dim>& box(std::uint32_t i) const noexcept { return grid_.boxes[i]; }
    [[nodiscard]] BoxId id(std::uint32_t i) const noexcept { return ids_[i]; }
    [[nodiscard]] const Filter& filter(std::uint32_t i) const noexcept { return filters_[i]; }
    /// A floor for the skin of moving boxes that have no size: a few of the finest cells, which
    /// are about the mean static.
    [[nodiscard]] double smallest_cell_side() const noexcept { return smallest_side_; }

    void clear() { *this = StaticGrid(); }

    /// Takes the statics (boxes, their ids and filters, as long as each other) and grids them.
    void build(std::vector<Box<Real, Dim>> boxes, std::vector<BoxId> ids, std::vector<Filter> filters) {
        // The grid keeps each static's input position as its id, which orders the ids and filters.
        grid_.build(
            std::span<const Box<Real, Dim>>(boxes), [](std::size_t i) { return static_cast<BoxId>(i); },
            [](std::size_t) { return true; });
        ids_.resize(ids.size());
        filters_.resize(filters.size());
        for (std::size_t p = 0; p < grid_.ids.size(); ++p) {
            ids_[p] = ids[static_cast<std::size_t>(grid_.ids[p])];
            filters_[p] = filters[static_cast<std::size_t>(grid_.ids[p])];
        }
        smallest_side_ = 0;
        if (!grid_.levels.empty() && std::isfinite(grid_.levels.front().side)) {
            smallest_side_ = tuning::static_cell_in_means * grid_.levels.front().side;
        }
    }

    /// Calls found(i) once for every static i that overlaps `query` (closed overlap).
    template <class Found>
    void query(const Box<Real, Dim>& query, Found&& found) const {
        grid_.query_positions(query, found);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return grid_.bytes_held() + ids_.capacity() * sizeof(BoxId) + filters_.capacity() * sizeof(Filter);
    }

private:
    GridIndex<Real, Dim> grid_;
    std::vector<BoxId> ids_;
    std::vector<Filter> filters_;
    double smallest_side_ = 0;
};

}  // namespace smb::detail
