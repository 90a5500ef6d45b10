// SPDX-License-Identifier: MIT
#include <CGAL/box_intersection_d.h>

#include <cstdint>

#include "peers/cgal_box.hpp"
#include "peers/peer_factories.hpp"

namespace smb::bench {
namespace {

template <int Dim>
class CgalBoxIntersectionPeer final : public StatelessPeer<Dim> {
protected:
    void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        pairs.clear();
        boxes_.resize(step.size());
        for (std::size_t i = 0; i < step.size(); ++i) boxes_[i] = {step.boxes[i].min, step.boxes[i].max, i};
        const auto ids = step.ids;
        auto report = [&pairs, ids](const CgalBox<Dim>& a, const CgalBox<Dim>& b) {
            pairs.push_back(ordered_pair(ids[a.index], ids[b.index]));
        };
        // CGAL's default cutoff (10) and the closed topology: touching boxes intersect.
        CGAL::box_self_intersection_d(boxes_.begin(), boxes_.end(), report, std::ptrdiff_t{10},
                                      CGAL::Box_intersection_d::CLOSED);
    }

private:
    std::vector<CgalBox<Dim>> boxes_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_cgal_box_intersection_peer() {
    return std::make_unique<CgalBoxIntersectionPeer<Dim>>();
}

template std::unique_ptr<Peer<2>> make_cgal_box_intersection_peer<2>();
template std::unique_ptr<Peer<3>> make_cgal_box_intersection_peer<3>();

}  // namespace smb::bench
