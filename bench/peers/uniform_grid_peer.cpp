// SPDX-License-Identifier: MIT
#include <sstream>

#include "peers/peer_factories.hpp"
#include "peers/uniform_grid.hpp"

namespace smb::bench {
namespace {

/// The uniform grid of peers/uniform_grid.hpp, rebuilt from the complete box set every step.
template <int Dim>
class UniformGridPeer final : public StatelessPeer<Dim> {
public:
    explicit UniformGridPeer(int threads) : grid_({}, threads) {}

    [[nodiscard]] std::string details_json() const override {
        std::ostringstream json;
        json << "\"grid_cells\":" << grid_.cell_count() << ",\"grid_cell_side\":" << grid_.cell_side(0)
             << ",\"grid_oversized\":" << grid_.oversized_count() << ",\"grid_lanes\":" << grid_.lanes();
        return json.str();
    }

protected:
    void find_pairs(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        pairs.clear();
        grid_.find_pairs(step.boxes, step.ids, pairs);
    }

private:
    UniformGrid<Dim> grid_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_uniform_grid_peer(int threads) {
    return std::make_unique<UniformGridPeer<Dim>>(threads);
}

template std::unique_ptr<Peer<2>> make_uniform_grid_peer<2>(int);
template std::unique_ptr<Peer<3>> make_uniform_grid_peer<3>(int);

}  // namespace smb::bench
