// SPDX-License-Identifier: MIT
#include <box2d/b2_dynamic_tree.h>

#include <algorithm>
#include <cstdint>
#include <memory>

#include "queries/query_peer.hpp"

namespace smb::bench {
namespace {

// Box2D 2.4's dynamic tree as b2World uses it: proxies created one by one (their boxes fattened
// by b2_aabbExtension), optionally rebuilt bottom-up afterwards; Query for boxes, RayCast for
// segments. A nearest cast clips the segment at each hit's entry (RayCastCallback returns the
// new fraction), as b2World::RayCast's closest-hit callbacks do.
class Box2dTreeQueryPeer final : public QueryPeer<2> {
public:
    explicit Box2dTreeQueryPeer(bool rebuilt) : rebuilt_(rebuilt) {}

    std::string name() const override { return rebuilt_ ? "Box2D b2DynamicTree (rebuilt)" : "Box2D b2DynamicTree"; }

    void build(std::span<const Box<float, 2>> boxes) override {
        tree_ = std::make_unique<b2DynamicTree>();  // it cannot be assigned
        boxes_ = boxes;
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            b2AABB aabb;
            aabb.lowerBound.Set(boxes[i].min[0], boxes[i].min[1]);
            aabb.upperBound.Set(boxes[i].max[0], boxes[i].max[1]);
            tree_->CreateProxy(aabb, reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
        }
        if (rebuilt_) tree_->RebuildBottomUp();
    }

    bool QueryCallback(std::int32_t proxy) {
        const std::size_t i = index_of(proxy);
        if (overlaps(*query_, boxes_[i])) query_out_->push_back(i);
        return true;
    }

    float RayCastCallback(const b2RayCastInput& input, std::int32_t proxy) {
        const std::size_t i = index_of(proxy);
        const auto t = ray_entry(*ray_, boxes_[i]);
        if (!t) return input.maxFraction;
        ray_out_->push_back({i, static_cast<float>(*t)});
        if (!nearest_) return input.maxFraction;
        // Clip at the hit, a little beyond it so a tie at the same entry is still visited.
        return std::min(input.maxFraction, static_cast<float>(*t / ray_->max_t) * 1.0001f + 1e-6f);
    }

    void query(const Box<float, 2>& q, std::vector<BoxId>& out) override {
        out.clear();
        query_ = &q;
        query_out_ = &out;
        b2AABB aabb;
        aabb.lowerBound.Set(q.min[0], q.min[1]);
        aabb.upperBound.Set(q.max[0], q.max[1]);
        tree_->Query(this, aabb);
    }

    void cast(const Ray<float, 2>& ray, RayHits mode, std::vector<RayHit<float>>& out) override {
        out.clear();
        ray_ = &ray;
        ray_out_ = &out;
        nearest_ = mode == RayHits::nearest;
        b2RayCastInput input;
        input.p1.Set(ray.origin[0], ray.origin[1]);
        input.p2.Set(ray.origin[0] + ray.direction[0] * ray.max_t, ray.origin[1] + ray.direction[1] * ray.max_t);
        input.maxFraction = 1;
        tree_->RayCast(this, input);
        finish_hits(mode, out);
    }

private:
    std::size_t index_of(std::int32_t proxy) const {
        return static_cast<std::size_t>(reinterpret_cast<std::uintptr_t>(tree_->GetUserData(proxy)));
    }

    bool rebuilt_;
    std::unique_ptr<b2DynamicTree> tree_ = std::make_unique<b2DynamicTree>();
    std::span<const Box<float, 2>> boxes_;
    const Box<float, 2>* query_ = nullptr;
    std::vector<BoxId>* query_out_ = nullptr;
    const Ray<float, 2>* ray_ = nullptr;
    std::vector<RayHit<float>>* ray_out_ = nullptr;
    bool nearest_ = false;
};

}  // namespace

std::unique_ptr<QueryPeer<2>> make_box2d_tree_query_peer(bool rebuilt) {
    return std::make_unique<Box2dTreeQueryPeer>(rebuilt);
}

}  // namespace smb::bench
