// SPDX-License-Identifier: MIT
#include "peers/peer_factories.hpp"

#include <span>
#include <type_traits>

#include "peers/smb_phases.hpp"
#include "smb/world.hpp"

namespace smb::bench {
namespace {

/// A World over Real coordinates. With Real = double, the float scene boxes are widened in
/// prepare(), untimed: a double application holds double boxes already. Widening is exact, so
/// both report the same pairs.
template <typename Real, int Dim>
class SmbWorldPeer final : public Peer<Dim> {
public:
    // Profiled, for the phases of details_json().
    explicit SmbWorldPeer(WorldSettings settings) : world_(profiled(settings)) {}

    void prepare(const SceneStep<Dim>& step) override {
        if constexpr (!std::is_same_v<Real, float>) {
            widened_.resize(step.boxes.size());
            for (std::size_t i = 0; i < step.boxes.size(); ++i) {
                for (int k = 0; k < Dim; ++k) {
                    widened_[i].min[k] = step.boxes[i].min[k];
                    widened_[i].max[k] = step.boxes[i].max[k];
                }
            }
        }
    }

    void build(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        world_.insert(step.ids, boxes_of(step));
        pairs.clear();  // as every peer: detect() then has no old pairs to keep
        world_.detect(pairs);
        phases_ = {};
    }

    void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        if (!step.removed_ids.empty()) world_.remove(step.removed_ids);
        const std::span<const Box<Real, Dim>> boxes = boxes_of(step);
        world_.update(step.ids.first(step.first_inserted), boxes.first(step.first_inserted));
        if (step.inserted_count() > 0)
            world_.insert(step.ids.subspan(step.first_inserted), boxes.subspan(step.first_inserted));
        pairs.clear();  // as every peer: detect() then has no old pairs to keep
        const DetectStats stats = world_.detect(pairs);
        phases_.add(world_.last_profile(), stats);
    }

    // Where detect() spends its time, averaged over the steps after the first.
    [[nodiscard]] std::string details_json() const override { return phases_.json(); }

private:
    static WorldSettings profiled(WorldSettings settings) {
        settings.profile = true;
        return settings;
    }

    [[nodiscard]] std::span<const Box<Real, Dim>> boxes_of(const SceneStep<Dim>& step) const {
        if constexpr (std::is_same_v<Real, float>)
            return step.boxes;
        else
            return widened_;
    }

    World<Real, Dim> world_;
    std::vector<Box<Real, Dim>> widened_;
    SmbPhases phases_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_smb_world_peer(const WorldSettings& settings) {
    return std::make_unique<SmbWorldPeer<float, Dim>>(settings);
}

template <int Dim>
std::unique_ptr<Peer<Dim>> make_smb_world_double_peer(const WorldSettings& settings) {
    return std::make_unique<SmbWorldPeer<double, Dim>>(settings);
}

template std::unique_ptr<Peer<2>> make_smb_world_peer<2>(const WorldSettings&);
template std::unique_ptr<Peer<3>> make_smb_world_peer<3>(const WorldSettings&);
template std::unique_ptr<Peer<2>> make_smb_world_double_peer<2>(const WorldSettings&);
template std::unique_ptr<Peer<3>> make_smb_world_double_peer<3>(const WorldSettings&);

}  // namespace smb::bench
