// SPDX-License-Identifier: MIT
#include <box2d/b2_dynamic_tree.h>

#include <cstdint>
#include <unordered_set>

#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

constexpr std::int32_t no_proxy = -1;

b2AABB to_box2d(const BenchBox<2>& box) {
    b2AABB aabb;
    aabb.lowerBound.Set(box.min[0], box.min[1]);
    aabb.upperBound.Set(box.max[0], box.max[1]);
    return aabb;
}

// Box2D 2.4 driven as b2World drives it: proxies move with MoveProxy (which re-inserts only
// those that left their fattened box), the moved ones query the tree for new candidate
// pairs, and a persistent candidate list (b2ContactManager's contacts) drops pairs whose fat
// boxes separated. The report is the candidates whose exact boxes overlap.
// The scenes move boxes by independent random jumps, not by velocities, so every move is
// passed as b2Body::SetTransform passes it: with zero displacement. A displacement would
// only stretch the fat box by 4x the last jump, in a direction the next jump ignores.
class Box2dDynamicTreePeer final : public Peer<2> {
public:
    void build(const SceneStep<2>& step, std::vector<Pair>& pairs) override {
        moved_.clear();
        for (std::size_t i = 0; i < step.size(); ++i) insert(step.ids[i], step.boxes[i]);
        pairs.clear();
        find_new_candidates(pairs);
    }

    void step(const SceneStep<2>& step, std::vector<Pair>& pairs) override {
        moved_.clear();
        for (BoxId id : step.removed_ids) remove(id);
        for (std::size_t i = 0; i < step.first_inserted; ++i) {
            const std::int32_t proxy = proxy_of_id_[step.ids[i]];
            box_of_proxy_[proxy] = step.boxes[i];
            if (tree_.MoveProxy(proxy, to_box2d(step.boxes[i]), b2Vec2_zero)) moved_.push_back(proxy);
        }
        pairs.clear();
        keep_live_candidates(pairs);
        for (std::size_t i = step.first_inserted; i < step.size(); ++i) insert(step.ids[i], step.boxes[i]);
        find_new_candidates(pairs);
    }

    // Called by b2DynamicTree::Query for each proxy whose fat box overlaps the query box.
    bool QueryCallback(std::int32_t other) {
        if (other == querying_) return true;
        // Both moved: the one with the larger proxy id finds the pair (as b2BroadPhase does).
        if (tree_.WasMoved(other) && other > querying_) return true;
        const std::uint64_t key = pair_key(querying_, other);
        if (!candidate_keys_.insert(key).second) return true;
        candidates_.push_back(key);
        report_if_exact(querying_, other, *sink_);
        return true;
    }

private:
    static std::uint64_t pair_key(std::int32_t a, std::int32_t b) {
        const auto low = static_cast<std::uint64_t>(std::min(a, b)), high = static_cast<std::uint64_t>(std::max(a, b));
        return low << 32 | high;
    }

    void insert(BoxId id, const BenchBox<2>& box) {
        const std::int32_t proxy = tree_.CreateProxy(to_box2d(box), nullptr);
        const auto slot = static_cast<std::size_t>(proxy);
        if (slot >= box_of_proxy_.size()) {
            box_of_proxy_.resize(slot + 1);
            id_of_proxy_.resize(slot + 1);
            alive_.resize(slot + 1, 0);
        }
        box_of_proxy_[slot] = box;
        id_of_proxy_[slot] = id;
        alive_[slot] = 1;
        if (id >= proxy_of_id_.size())
            proxy_of_id_.resize(std::max<std::size_t>(id + 1, 2 * proxy_of_id_.size()), no_proxy);
        proxy_of_id_[id] = proxy;
        moved_.push_back(proxy);
    }

    void remove(BoxId id) {
        const std::int32_t proxy = proxy_of_id_[id];
        tree_.DestroyProxy(proxy);
        alive_[static_cast<std::size_t>(proxy)] = 0;
        proxy_of_id_[id] = no_proxy;
    }

    void report_if_exact(std::int32_t a, std::int32_t b, std::vector<Pair>& pairs) const {
        const auto first = static_cast<std::size_t>(a), second = static_cast<std::size_t>(b);
        if (overlaps(box_of_proxy_[first], box_of_proxy_[second]))
            pairs.push_back(ordered_pair(id_of_proxy_[first], id_of_proxy_[second]));
    }

    // Runs before this step's insertions, so a proxy id freed by a removal cannot yet stand
    // for a new box.
    void keep_live_candidates(std::vector<Pair>& pairs) {
        std::size_t kept = 0;
        for (const std::uint64_t key : candidates_) {
            const auto a = static_cast<std::int32_t>(key >> 32), b = static_cast<std::int32_t>(key & 0xffffffffu);
            const bool live = alive_[static_cast<std::size_t>(a)] && alive_[static_cast<std::size_t>(b)] &&
                              b2TestOverlap(tree_.GetFatAABB(a), tree_.GetFatAABB(b));
            if (!live) {
                candidate_keys_.erase(key);
                continue;
            }
            candidates_[kept++] = key;
            report_if_exact(a, b, pairs);
        }
        candidates_.resize(kept);
    }

    void find_new_candidates(std::vector<Pair>& pairs) {
        sink_ = &pairs;
        for (const std::int32_t proxy : moved_) {
            querying_ = proxy;
            tree_.Query(this, tree_.GetFatAABB(proxy));
        }
        for (const std::int32_t proxy : moved_) tree_.ClearMoved(proxy);
    }

    b2DynamicTree tree_;
    std::vector<BenchBox<2>> box_of_proxy_;
    std::vector<BoxId> id_of_proxy_;
    std::vector<std::uint8_t> alive_;
    std::vector<std::int32_t> proxy_of_id_;  // indexed by id: the scenes' ids are dense
    std::vector<std::int32_t> moved_;
    std::vector<std::uint64_t> candidates_;
    std::unordered_set<std::uint64_t> candidate_keys_;
    std::int32_t querying_ = no_proxy;
    std::vector<Pair>* sink_ = nullptr;
};

}  // namespace

std::unique_ptr<Peer<2>> make_box2d_dynamic_tree_peer() { return std::make_unique<Box2dDynamicTreePeer>(); }

}  // namespace smb::bench
