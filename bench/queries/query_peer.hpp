// SPDX-License-Identifier: MIT
#pragma once
// One index answering box queries and ray casts in the query comparison (query_compare.cpp):
// smb::BoxIndex, Bullet's btDbvt, Box2D's b2DynamicTree. Each reports exact answers, by the
// definitions smb uses (smb::overlaps, smb::ray_entry), so that their answers can be compared;
// the exact test of each candidate is part of every method's cost.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "smb/box.hpp"
#include "smb/query.hpp"

namespace smb::bench {

template <int Dim>
class QueryPeer {
public:
    using box_type = Box<float, Dim>;
    using ray_type = Ray<float, Dim>;

    virtual ~QueryPeer() = default;
    [[nodiscard]] virtual std::string name() const = 0;
    /// Box i under id i.
    virtual void build(std::span<const box_type> boxes) = 0;
    /// The ids of the boxes overlapping q, in any order.
    virtual void query(const box_type& q, std::vector<BoxId>& out) = 0;
    /// The nearest hit, or every hit sorted by (t, id).
    virtual void cast(const ray_type& ray, RayHits mode, std::vector<RayHit<float>>& out) = 0;
    /// Heap bytes the index holds, where the method can say (0: it cannot).
    [[nodiscard]] virtual std::size_t bytes_held() const { return 0; }
};

std::unique_ptr<QueryPeer<2>> make_smb_query_peer_2d();
std::unique_ptr<QueryPeer<3>> make_smb_query_peer_3d();
#ifdef SMB_BENCH_HAVE_BULLET
std::unique_ptr<QueryPeer<3>> make_bullet_dbvt_query_peer(bool top_down);
#endif
#ifdef SMB_BENCH_HAVE_BOX2D
std::unique_ptr<QueryPeer<2>> make_box2d_tree_query_peer(bool rebuilt);
#endif

/// Sorts hits by (t, id) and keeps the first for RayHits::nearest: what the tree peers do with
/// the exact hits their traversal found.
inline void finish_hits(RayHits mode, std::vector<RayHit<float>>& hits) {
    auto before = [](const RayHit<float>& a, const RayHit<float>& b) { return a.t != b.t ? a.t < b.t : a.id < b.id; };
    if (mode == RayHits::nearest) {
        if (hits.size() > 1) {
            auto best = hits[0];
            for (const auto& h : hits) {
                if (before(h, best)) best = h;
            }
            hits.assign(1, best);
        }
        return;
    }
    std::sort(hits.begin(), hits.end(), before);
}

}  // namespace smb::bench
