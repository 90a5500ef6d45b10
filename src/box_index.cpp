// SPDX-License-Identifier: MIT
#include "smb/box_index.hpp"

#include <algorithm>
#include <string>

#include "core/invalid_box.hpp"
#include "core/shortest_number.hpp"
#include "instantiations.hpp"
#include "query/grid_index.hpp"
#include "query/grid_ray.hpp"

namespace smb {

namespace {

template <std::floating_point Real, int Dim>
void check_query(const Box<Real, Dim>& box, std::size_t index) {
    if (is_valid(box)) return;
    // describe_invalid_box names a box id; here the box is the caller's query number `index`.
    std::string message = detail::describe_invalid_box(static_cast<BoxId>(index), box);
    message.replace(0, 3, "query: query");
    throw InvalidBoxError(message);
}

template <std::floating_point Real, int Dim>
void check_ray(const Ray<Real, Dim>& ray) {
    if (is_valid(ray)) return;
    auto list = [](const std::array<Real, Dim>& v) {
        std::string s = "(";
        for (int k = 0; k < Dim; ++k) s += (k ? ", " : "") + detail::shortest_number(v[k]);
        return s + ")";
    };
    const std::string start = "cast_ray: invalid ray (origin " + list(ray.origin) + ", direction " +
                              list(ray.direction) + ", max_t " + detail::shortest_number(ray.max_t) + "): ";
    for (int k = 0; k < Dim; ++k) {
        if (!std::isfinite(ray.origin[k])) throw ArgumentError(start + "the origin is not finite");
        if (!std::isfinite(ray.direction[k])) throw ArgumentError(start + "the direction is not finite");
    }
    if (std::isnan(ray.max_t) || ray.max_t < 0) throw ArgumentError(start + "max_t must be >= 0");
    throw ArgumentError(start + "a zero direction needs a finite max_t (a zero-length segment)");
}

/// Builds into the index's grid, reusing its memory (a rebuild every step would otherwise pay the
/// page faults of fresh arrays). The input is checked before; should the build still throw (out of
/// memory, or more than 2^32 entries), the index is left empty.
template <class Grid, class Build>
void rebuild_grid(std::unique_ptr<Grid>& grid, Build&& build) {
    if (!grid) grid = std::make_unique<Grid>();
    try {
        build(*grid);
    } catch (...) {
        grid.reset();
        throw;
    }
}

/// Checks `boxes` (box i named id_of(i) in the error) and builds the grid of all of them.
template <class Grid, std::floating_point Real, int Dim, class IdOf>
void build_checked(std::unique_ptr<Grid>& grid, std::span<const Box<Real, Dim>> boxes, IdOf id_of) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!is_valid(boxes[i])) throw InvalidBoxError(detail::describe_invalid_box(id_of(i), boxes[i]));
    }
    rebuild_grid(grid, [&](Grid& built) { built.build(boxes, id_of, [](std::size_t) { return true; }); });
}

}  // namespace

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>::BoxIndex() = default;

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>::BoxIndex(std::span<const box_type> boxes) : BoxIndex() {
    build(boxes);
}

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>::BoxIndex(std::span<const BoxId> ids, std::span<const box_type> boxes) : BoxIndex() {
    build(ids, boxes);
}

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>::~BoxIndex() = default;

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>::BoxIndex(BoxIndex&&) noexcept = default;

template <std::floating_point Real, int Dim>
BoxIndex<Real, Dim>& BoxIndex<Real, Dim>::operator=(BoxIndex&&) noexcept = default;

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::build(std::span<const box_type> boxes) {
    build_checked(grid_, boxes, [](std::size_t i) { return static_cast<BoxId>(i); });
}

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::build(std::span<const BoxId> ids, std::span<const box_type> boxes) {
    if (ids.size() != boxes.size()) {
        throw ArgumentError("BoxIndex: " + std::to_string(ids.size()) + " ids but " + std::to_string(boxes.size()) +
                            " boxes");
    }
    build_checked(grid_, boxes, [&](std::size_t i) { return ids[i]; });
}

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::build_from_store(std::span<const box_type> boxes, std::span<const BoxId> ids,
                                           const std::function<bool(std::size_t)>& keep) {
    rebuild_grid(grid_, [&](detail::GridIndex<Real, Dim>& grid) {
        grid.build(
            boxes, [&](std::size_t i) { return ids[i]; }, keep);
    });
}

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::query(const box_type& query, std::vector<BoxId>& out) const {
    check_query(query, 0);
    out.clear();
    if (grid_) grid_->query(query, [&](BoxId id) { out.push_back(id); });
}

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::query(std::span<const box_type> queries, std::vector<QueryHit>& out) const {
    for (std::size_t q = 0; q < queries.size(); ++q) check_query(queries[q], q);
    out.clear();
    if (!grid_) return;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        grid_->query(queries[q], [&](BoxId id) { out.push_back(QueryHit{q, id}); });
    }
}

template <std::floating_point Real, int Dim>
void BoxIndex<Real, Dim>::cast_ray(const ray_type& ray, RayHits mode, std::vector<hit_type>& out) const {
    check_ray(ray);
    if (grid_) {
        detail::cast_ray(*grid_, ray, mode, out);
    } else {
        out.clear();
    }
}

template <std::floating_point Real, int Dim>
std::size_t BoxIndex<Real, Dim>::size() const noexcept {
    return grid_ ? grid_->boxes.size() : 0;
}

template <std::floating_point Real, int Dim>
std::size_t BoxIndex<Real, Dim>::bytes_held() const noexcept {
    return grid_ ? sizeof(*grid_) + grid_->bytes_held() : 0;
}

#define SMB_INSTANTIATE(Real, Dim) template class BoxIndex<Real, Dim>;
SMB_FOR_EACH_BOX_TYPE(SMB_INSTANTIATE)
#undef SMB_INSTANTIATE

}  // namespace smb
