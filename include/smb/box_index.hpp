// SPDX-License-Identifier: MIT
#pragma once
// A static index over a set of boxes for region queries and ray casts.

#include <concepts>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "smb/box.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/query.hpp"

namespace smb {

namespace detail {
template <std::floating_point Real, int Dim>
class GridIndex;
}  // namespace detail

template <std::floating_point Real, int Dim>
class World;

/// The boxes of one moment, indexed for queries: every box overlapping a query box (closed, as
/// smb::overlaps), and the boxes a ray or segment enters (as smb::ray_entry). It holds a copy of
/// the boxes, so it answers for the boxes as they were when it was built; build it again after
/// they change (O(N)).
///
/// Inside: a hierarchy of uniform grids. The finest cell side is about the boxes' mean extent
/// (made coarser so that there are at most about 2N cells); each box sits on the finest level
/// whose cell is at least as large as the box (so it reaches at most one cell past the cell of
/// its lower corner) and is kept once, in the run of its lower corner's cell. A huge box thus
/// lands on a coarse level with few cells. A box query reads, on each non-empty level, the runs
/// of the cells from its lower corner less the level's widest box up to its upper corner; a ray
/// walks the cells it crosses on each level, slab by slab along its dominant axis, and a nearest
/// cast stops once the cells ahead start beyond the best hit, so its cost grows with the cells
/// crossed, not with N. The cells are computed conservatively (the walk is
/// widened by a millionth of a cell, and more far from the scene), then every candidate is tested
/// exactly, so rays along faces, edges and cell boundaries miss nothing.
///
/// Errors: building with an invalid box throws InvalidBoxError (and mismatched spans
/// ArgumentError), a query with an invalid box InvalidBoxError, a cast with an invalid ray
/// (smb::is_valid) ArgumentError; the index and the output vector are then unchanged.
///
/// Thread safety: the queries are const and keep no state: one index may serve many threads.
template <std::floating_point Real, int Dim>
class BoxIndex {
public:
    using real_type = Real;
    using box_type = Box<Real, Dim>;
    using ray_type = Ray<Real, Dim>;
    using hit_type = RayHit<Real>;
    static constexpr int dimension = Dim;

    /// An empty index: every query answers nothing.
    BoxIndex();
    /// Box i under id i.
    explicit BoxIndex(std::span<const box_type> boxes);
    /// boxes[i] under ids[i]. Ids need not be distinct (a repeated id is reported once per box).
    BoxIndex(std::span<const BoxId> ids, std::span<const box_type> boxes);
    ~BoxIndex();
    BoxIndex(BoxIndex&&) noexcept;
    BoxIndex& operator=(BoxIndex&&) noexcept;
    BoxIndex(const BoxIndex&) = delete;
    BoxIndex& operator=(const BoxIndex&) = delete;

    /// Replaces the indexed boxes (box i under id i), reusing the index's memory. An invalid box
    /// throws before anything changes; should the build itself fail (out of memory, more than
    /// 2^32 - 2 boxes or cell entries), the index is left empty.
    void build(std::span<const box_type> boxes);
    void build(std::span<const BoxId> ids, std::span<const box_type> boxes);

    /// Replaces `out` by the id of every box that overlaps `query` (touching counts), each once,
    /// in an unspecified but deterministic order.
    void query(const box_type& query, std::vector<BoxId>& out) const;
    /// Replaces `out` by every (query index, id) with boxes[id] overlapping queries[index], sorted
    /// by query index, and within one query in the order of the single query.
    void query(std::span<const box_type> queries, std::vector<QueryHit>& out) const;
    /// Replaces `out` by the boxes `ray` enters within [0, max_t]: the nearest (least t, then
    /// least id; nothing if none) or all of them sorted by (t, id).
    void cast_ray(const ray_type& ray, RayHits mode, std::vector<hit_type>& out) const;

    [[nodiscard]] std::size_t size() const noexcept;
    [[nodiscard]] bool empty() const noexcept { return size() == 0; }
    /// Heap bytes the index holds.
    [[nodiscard]] std::size_t bytes_held() const noexcept;

private:
    friend class World<Real, Dim>;
    /// The world's rebuild: its slots, valid boxes, those with keep(slot) (the living ones).
    void build_from_store(std::span<const box_type> boxes, std::span<const BoxId> ids,
                          const std::function<bool(std::size_t)>& keep);

    std::unique_ptr<detail::GridIndex<Real, Dim>> grid_;
};

using BoxIndex2f = BoxIndex<float, 2>;
using BoxIndex2d = BoxIndex<double, 2>;
using BoxIndex3f = BoxIndex<float, 3>;
using BoxIndex3d = BoxIndex<double, 3>;

}  // namespace smb
