// SPDX-License-Identifier: MIT
#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

template <int Dim>
class BruteForcePeer final : public StatelessPeer<Dim> {
protected:
    void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        pairs.clear();
        const std::size_t count = step.size();
        for (std::size_t i = 0; i < count; ++i) {
            for (std::size_t j = i + 1; j < count; ++j) {
                if (overlaps(step.boxes[i], step.boxes[j])) pairs.push_back(ordered_pair(step.ids[i], step.ids[j]));
            }
        }
    }
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_brute_force_peer() {
    return std::make_unique<BruteForcePeer<Dim>>();
}

template std::unique_ptr<Peer<2>> make_brute_force_peer<2>();
template std::unique_ptr<Peer<3>> make_brute_force_peer<3>();

}  // namespace smb::bench
