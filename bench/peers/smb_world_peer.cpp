#include "peers/peer_factories.hpp"

#include "smb/world.hpp"

namespace smb::bench {
namespace {

template <int Dim>
class SmbWorldPeer final : public Peer<Dim> {
public:
    void build(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        world_.insert(step.ids, step.boxes);
        world_.detect(pairs);
    }

    void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        if (!step.removed_ids.empty()) world_.remove(step.removed_ids);
        world_.update(step.ids.first(step.first_inserted), step.boxes.first(step.first_inserted));
        if (step.inserted_count() > 0)
            world_.insert(step.ids.subspan(step.first_inserted), step.boxes.subspan(step.first_inserted));
        world_.detect(pairs);
    }

private:
    World<float, Dim> world_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_smb_world_peer() {
    return std::make_unique<SmbWorldPeer<Dim>>();
}

template std::unique_ptr<Peer<2>> make_smb_world_peer<2>();
template std::unique_ptr<Peer<3>> make_smb_world_peer<3>();

}  // namespace smb::bench
