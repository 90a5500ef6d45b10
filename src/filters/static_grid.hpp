// SPDX-License-Identifier: MIT
#pragma once
// The static boxes of a World, copied once, and a uniform grid over them that finds the statics
// overlapping a query box. It is built when the statics change and read by every moving box
// that left its fat box (static_contacts.hpp). The statics are sorted by the cell of their lower
// corner (their home cell). A small static (no wider than a cell on any axis, most of them, as
// cells are about twice the mean static) is found through its home cell alone: a query visits
// the home cells from its lower corner less the widest small static up to its upper corner, and
// on each row of cells along the first axis those statics are one contiguous run of the sorted
// array, read in order, each static once. A wider static is listed in every cell it covers
// (cells in CSR form) and reported from one of them. A static that would span more than
// kMaxSpan cells on some axis (a floor under a pile of grains) is kept apart and tested by every
// query, so that one large box cannot fill the grid with millions of entries.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "smb/box.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class StaticGrid {
public:
    using box_type = Box<Real, Dim>;

    [[nodiscard]] std::size_t size() const noexcept { return boxes_.size(); }
    [[nodiscard]] bool empty() const noexcept { return boxes_.empty(); }
    [[nodiscard]] const box_type& box(std::uint32_t i) const noexcept { return boxes_[i]; }
    [[nodiscard]] BoxId id(std::uint32_t i) const noexcept { return ids_[i]; }
    [[nodiscard]] const Filter& filter(std::uint32_t i) const noexcept { return filters_[i]; }
    /// The smallest side of a cell: a floor for the skin of moving boxes that have no size.
    [[nodiscard]] double smallest_cell_side() const noexcept { return smallest_side_; }

    void clear() { *this = StaticGrid(); }

    /// Takes the statics (boxes, their ids and filters, as long as each other) and grids them.
    void build(std::vector<box_type> boxes, std::vector<BoxId> ids, std::vector<Filter> filters) {
        boxes_ = std::move(boxes);
        ids_ = std::move(ids);
        filters_ = std::move(filters);
        start_.clear();
        items_.clear();
        home_start_.clear();
        oversized_.clear();
        reach_.fill(0);
        if (boxes_.empty()) return;
        choose_cells();
        order_by_home_cell();
        // The wider statics, listed in every cell they cover: two passes, count per cell, then
        // place (CSR).
        start_.assign(cell_count_ + 1, 0);
        const std::size_t wider = home_start_[cell_count_];
        for (std::size_t i = wider; i < boxes_.size(); ++i) {
            std::array<std::size_t, Dim> lo{}, hi{};
            span_of(boxes_[i], lo, hi);
            bool listed = true;
            for (int k = 0; k < Dim; ++k) listed = listed && hi[k] - lo[k] < kMaxSpan;
            if (!listed) {
                oversized_.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            for_cells(lo, hi, [&](std::size_t cell, const std::array<std::size_t, Dim>&) { ++start_[cell + 1]; });
        }
        for (std::size_t c = 0; c < cell_count_; ++c) start_[c + 1] += start_[c];
        items_.resize(start_[cell_count_]);
        std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
        std::size_t next_oversized = 0;
        for (std::size_t i = wider; i < boxes_.size(); ++i) {
            if (next_oversized < oversized_.size() && oversized_[next_oversized] == i) {
                ++next_oversized;
                continue;
            }
            std::array<std::size_t, Dim> lo{}, hi{};
            span_of(boxes_[i], lo, hi);
            for_cells(lo, hi, [&](std::size_t cell, const std::array<std::size_t, Dim>&) {
                items_[fill[cell]++] = static_cast<std::uint32_t>(i);
            });
        }
    }

    /// Calls found(i) once for every static i that overlaps `query` (closed overlap).
    template <class Found>
    void query(const box_type& query, Found&& found) const {
        if (boxes_.empty()) return;
        for (const std::uint32_t i : oversized_) {
            if (overlaps(boxes_[i], query)) found(i);
        }
        std::array<std::size_t, Dim> lo{}, hi{};
        span_of(query, lo, hi);
        // The small statics, by home cell. A static that overlaps the query has its lower
        // corner at least query.min - reach on every axis; `from` is rounded down from that, so
        // the cell of the static's corner is at least the cell of `from` (cell_on never
        // decreases).
        std::array<std::size_t, Dim> from{};
        for (int k = 0; k < Dim; ++k)
            from[k] = cell_on(k, std::nextafter(static_cast<double>(query.min[k]) - reach_[k], -INFINITY));
        const auto run = [&](std::size_t first_cell, std::size_t last_cell) {
            for (std::uint32_t i = home_start_[first_cell]; i < home_start_[last_cell + 1]; ++i) {
                if (overlaps(boxes_[i], query)) found(i);
            }
        };
        if constexpr (Dim == 2) {
            for (std::size_t y = from[1]; y <= hi[1]; ++y) run(y * cells_[0] + from[0], y * cells_[0] + hi[0]);
        } else {
            for (std::size_t z = from[2]; z <= hi[2]; ++z) {
                for (std::size_t y = from[1]; y <= hi[1]; ++y) {
                    const std::size_t row = (z * cells_[1] + y) * cells_[0];
                    run(row + from[0], row + hi[0]);
                }
            }
        }
        if (items_.empty()) return;
        // The wider statics, through every cell they cover.
        for_cells(lo, hi, [&](std::size_t cell, const std::array<std::size_t, Dim>& at) {
            for (std::uint32_t e = start_[cell]; e < start_[cell + 1]; ++e) {
                const std::uint32_t i = items_[e];
                const box_type& b = boxes_[i];
                if (!overlaps(b, query)) continue;
                // A static listed in several cells the query covers is reported from one of
                // them only: the cell of the lower corner of their intersection.
                bool first = true;
                for (int k = 0; k < Dim; ++k) first = first && cell_on(k, std::max(b.min[k], query.min[k])) == at[k];
                if (first) found(i);
            }
        });
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return boxes_.capacity() * sizeof(box_type) + ids_.capacity() * sizeof(BoxId) +
               filters_.capacity() * sizeof(Filter) +
               (start_.capacity() + items_.capacity() + home_start_.capacity() + oversized_.capacity()) *
                   sizeof(std::uint32_t);
    }

private:
    /// Whether a static is small: no wider than a cell on any axis (any width on an axis of one
    /// cell).
    [[nodiscard]] bool small(const box_type& b) const noexcept {
        bool fits = true;
        for (int k = 0; k < Dim; ++k) {
            const double width = static_cast<double>(b.max[k]) - static_cast<double>(b.min[k]);
            fits = fits && (cells_[k] == 1 || width * inverse_side_[k] <= 1);
        }
        return fits;
    }

    /// Sorts the small statics by home cell (a counting sort), the others after them, and sets
    /// home_start_ (cell c's small statics are [home_start_[c], home_start_[c + 1])) and reach_
    /// (at least the widest small static on each axis).
    void order_by_home_cell() {
        std::vector<std::size_t> home(boxes_.size());
        std::vector<std::size_t> first(cell_count_ + 2, 0);
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            const box_type& b = boxes_[i];
            std::size_t cell = cell_count_;  // the bucket of the wider statics, last
            if (small(b)) {
                std::array<std::size_t, Dim> lo{}, hi{};
                span_of(b, lo, hi);
                for_cells(lo, lo, [&](std::size_t c, const std::array<std::size_t, Dim>&) { cell = c; });
                for (int k = 0; k < Dim; ++k) {
                    const double width = static_cast<double>(b.max[k]) - static_cast<double>(b.min[k]);
                    reach_[k] = std::max(reach_[k], std::nextafter(width, INFINITY));
                }
            }
            home[i] = cell;
            ++first[cell + 1];
        }
        for (std::size_t c = 0; c <= cell_count_; ++c) first[c + 1] += first[c];
        home_start_.assign(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(cell_count_) + 1);
        std::vector<box_type> boxes(boxes_.size());
        std::vector<BoxId> ids(ids_.size());
        std::vector<Filter> filters(filters_.size());
        for (std::size_t i = 0; i < boxes_.size(); ++i) {
            const std::size_t to = first[home[i]]++;
            boxes[to] = boxes_[i];
            ids[to] = ids_[i];
            filters[to] = filters_[i];
        }
        boxes_.swap(boxes);
        ids_.swap(ids);
        filters_.swap(filters);
    }

    static constexpr std::size_t kMaxSpan = 4;

    /// Cells about twice the mean static on each axis (so that a static lies in few cells and a
    /// cell holds few statics), and no more cells than twice the statics, whatever the region.
    void choose_cells() {
        std::array<double, Dim> lo{}, hi{}, mean{};
        lo.fill(INFINITY);
        hi.fill(-INFINITY);
        for (const box_type& b : boxes_) {
            for (int k = 0; k < Dim; ++k) {
                lo[k] = std::min(lo[k], static_cast<double>(b.min[k]));
                hi[k] = std::max(hi[k], static_cast<double>(b.max[k]));
                mean[k] += static_cast<double>(b.max[k]) - static_cast<double>(b.min[k]);
            }
        }
        const auto n = static_cast<double>(boxes_.size());
        const double per_axis_cap = std::ceil(std::pow(2.0 * n, 1.0 / Dim));
        std::array<double, Dim> count{};
        double total = 1;
        for (int k = 0; k < Dim; ++k) {
            mean[k] /= n;
            const double range = hi[k] - lo[k];
            double c = mean[k] > 0 ? std::floor(range / (2 * mean[k])) : per_axis_cap;
            c = std::clamp(c, 1.0, per_axis_cap);
            // A flat extent, or one that overflows (boxes near the ends of double's range, where
            // the quotient above is NaN), puts every static in one cell on that axis.
            if (!(range > 0) || !std::isfinite(range) || !std::isfinite(c)) c = 1;
            count[k] = c;
            total *= c;
        }
        if (total > 2 * n) {
            const double shrink = std::pow(total / (2 * n), 1.0 / Dim);
            for (int k = 0; k < Dim; ++k) count[k] = std::max(1.0, std::floor(count[k] / shrink));
        }
        cell_count_ = 1;
        smallest_side_ = INFINITY;
        for (int k = 0; k < Dim; ++k) {
            cells_[k] = static_cast<std::size_t>(count[k]);
            cell_count_ *= cells_[k];
            origin_[k] = lo[k];
            const double range = hi[k] - lo[k];
            const bool spread = range > 0 && std::isfinite(range) && std::isfinite(count[k] / range);
            inverse_side_[k] = spread ? count[k] / range : 0;
            if (spread) smallest_side_ = std::min(smallest_side_, range / count[k]);
        }
        if (!std::isfinite(smallest_side_)) smallest_side_ = 0;
    }

    [[nodiscard]] std::size_t cell_on(int k, double x) const noexcept {
        const double t = (static_cast<double>(x) - origin_[k]) * inverse_side_[k];
        if (!(t > 0)) return 0;
        const double top = static_cast<double>(cells_[k] - 1);
        return static_cast<std::size_t>(std::min(t, top));
    }

    void span_of(const box_type& b, std::array<std::size_t, Dim>& lo, std::array<std::size_t, Dim>& hi) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            lo[k] = cell_on(k, b.min[k]);
            hi[k] = cell_on(k, b.max[k]);
        }
    }

    /// visit(cell, coordinates) for every cell from lo to hi (inclusive) on every axis.
    template <class Visit>
    void for_cells(const std::array<std::size_t, Dim>& lo, const std::array<std::size_t, Dim>& hi,
                   Visit&& visit) const {
        std::array<std::size_t, Dim> at{};
        if constexpr (Dim == 2) {
            for (at[1] = lo[1]; at[1] <= hi[1]; ++at[1])
                for (at[0] = lo[0]; at[0] <= hi[0]; ++at[0]) visit(at[1] * cells_[0] + at[0], at);
        } else {
            for (at[2] = lo[2]; at[2] <= hi[2]; ++at[2])
                for (at[1] = lo[1]; at[1] <= hi[1]; ++at[1])
                    for (at[0] = lo[0]; at[0] <= hi[0]; ++at[0])
                        visit((at[2] * cells_[1] + at[1]) * cells_[0] + at[0], at);
        }
    }

    std::vector<box_type> boxes_;
    std::vector<BoxId> ids_;
    std::vector<Filter> filters_;
    std::array<double, Dim> origin_{};
    std::array<double, Dim> inverse_side_{};
    std::array<std::size_t, Dim> cells_{};
    std::size_t cell_count_ = 0;
    double smallest_side_ = 0;
    std::vector<std::uint32_t> home_start_;  // the small statics by home cell (see order_by_home_cell)
    std::array<double, Dim> reach_{};        // at least the widest small static, per axis
    std::vector<std::uint32_t> start_;       // the wider statics: cell c's are items_[start_[c], start_[c + 1])
    std::vector<std::uint32_t> items_;
    std::vector<std::uint32_t> oversized_;
};

}  // namespace smb::detail
