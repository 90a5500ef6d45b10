// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cstdint>

#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

// Sorting (key, index) records rather than indices keeps the sort's comparisons in cache.
struct SortRecord {
    float min_x;
    std::uint32_t index;
};

template <int Dim>
class BoxPruningPeer final : public StatelessPeer<Dim> {
protected:
    void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        pairs.clear();
        const std::size_t count = step.size();
        order_.resize(count);
        for (std::size_t i = 0; i < count; ++i) order_[i] = {step.boxes[i].min[0], static_cast<std::uint32_t>(i)};
        std::sort(order_.begin(), order_.end(), [](const SortRecord& a, const SortRecord& b) {
            return a.min_x < b.min_x || (a.min_x == b.min_x && a.index < b.index);
        });
        for (std::size_t i = 0; i < count; ++i) {
            const BenchBox<Dim>& box = step.boxes[order_[i].index];
            const float max_x = box.max[0];
            for (std::size_t j = i + 1; j < count && order_[j].min_x <= max_x; ++j) {
                const std::uint32_t other = order_[j].index;
                if (overlaps(box, step.boxes[other]))
                    pairs.push_back(ordered_pair(step.ids[order_[i].index], step.ids[other]));
            }
        }
    }

private:
    std::vector<SortRecord> order_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_box_pruning_peer() {
    return std::make_unique<BoxPruningPeer<Dim>>();
}

template std::unique_ptr<Peer<2>> make_box_pruning_peer<2>();
template std::unique_ptr<Peer<3>> make_box_pruning_peer<3>();

}  // namespace smb::bench
