// SPDX-License-Identifier: MIT
#include <sstream>

#include "peers/peer_factories.hpp"
#include "peers/uniform_grid.hpp"
#include "smb/workload/swap_remove_mirror.hpp"

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

/// The same grid over an array the simulation keeps (smb/workload/swap_remove_mirror.hpp), which
/// it renumbers in the grid's cell order after the build and then every `renumber_every` steps,
/// timed with the detection before it: a caller that sorts its bodies in space makes any broad
/// phase's gather stream, not only smb's (smb_detector_sorted renumbers in smb's order).
template <int Dim>
class SortedUniformGridPeer final : public Peer<Dim> {
public:
    explicit SortedUniformGridPeer(std::size_t renumber_every) : grid_({}, 1), renumber_every_(renumber_every) {}

    /// Untimed: the simulation's own array follows the scene.
    void prepare(const SceneStep<Dim>& step) override {
        mirror_.follow(step.removed_ids, step.ids.subspan(step.first_inserted), step.ids, step.boxes);
    }
    void build(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override {
        find_pairs(pairs);
        renumber();
    }
    void step(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override {
        find_pairs(pairs);
        if (renumber_every_ > 0 && ++steps_ % renumber_every_ == 0) renumber();
    }

private:
    void find_pairs(std::vector<Pair>& pairs) {
        pairs.clear();
        grid_.find_pairs(mirror_.boxes(), mirror_.ids(), pairs);
    }
    void renumber() {
        const std::span<const std::uint32_t> order = grid_.order();
        if (order.size() == mirror_.boxes().size()) mirror_.renumber(order);
    }

    workload::SwapRemoveMirror<BenchBox<Dim>> mirror_;
    UniformGrid<Dim> grid_;
    std::size_t renumber_every_ = 0;
    std::size_t steps_ = 0;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_uniform_grid_peer(int threads) {
    return std::make_unique<UniformGridPeer<Dim>>(threads);
}

template std::unique_ptr<Peer<2>> make_uniform_grid_peer<2>(int);
template std::unique_ptr<Peer<3>> make_uniform_grid_peer<3>(int);

template <int Dim>
std::unique_ptr<Peer<Dim>> make_sorted_uniform_grid_peer(std::size_t renumber_every) {
    return std::make_unique<SortedUniformGridPeer<Dim>>(renumber_every);
}

template std::unique_ptr<Peer<2>> make_sorted_uniform_grid_peer<2>(std::size_t);
template std::unique_ptr<Peer<3>> make_sorted_uniform_grid_peer<3>(std::size_t);

}  // namespace smb::bench
