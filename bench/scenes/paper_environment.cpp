// SPDX-License-Identifier: MIT
#include "scenes/paper_environment.hpp"

#include <stdexcept>
#include <vector>

#include "smb/workload/dynamic_environment.hpp"

namespace smb::bench {
namespace {

// Adapts smb::workload's environment (double boxes, arrays in increasing id order, so the
// survivors come before the fresh ids) to the comparison's float steps.
template <int Dim>
class PaperEnvironment final : public Scene<Dim> {
public:
    explicit PaperEnvironment(const workload::EnvironmentParams& params) : environment_(params) {}

    const SceneStep<Dim>& advance() override {
        std::size_t first_inserted = 0;
        if (started_) {
            const auto& changes = environment_.step();
            removed_ids_.assign(changes.removed_ids.begin(), changes.removed_ids.end());
            first_inserted = changes.updated_ids.size();
            ++step_.index;
        }
        started_ = true;
        const auto boxes = environment_.boxes();
        boxes_.resize(boxes.size());
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            for (int k = 0; k < Dim; ++k) {
                boxes_[i].min[k] = static_cast<float>(boxes[i].min[k]);
                boxes_[i].max[k] = static_cast<float>(boxes[i].max[k]);
            }
        }
        step_.ids = environment_.ids();
        step_.boxes = boxes_;
        step_.removed_ids = removed_ids_;
        step_.first_inserted = first_inserted;
        return step_;
    }

private:
    workload::DynamicEnvironment<Dim> environment_;
    bool started_ = false;
    std::vector<BenchBox<Dim>> boxes_;
    std::vector<BoxId> removed_ids_;
    SceneStep<Dim> step_;
};

constexpr double paper_density = 0.4;
constexpr double paper_size_ratio = 2.5;
constexpr double sparse_size_ratio = 10.0;
constexpr double sparse_cube_side = 200.0;

}  // namespace

template <int Dim>
std::unique_ptr<Scene<Dim>> make_paper_scene(const SceneSpec& spec) {
    workload::EnvironmentParams params;
    params.box_count = spec.boxes;
    params.packing_density = paper_density;
    params.size_ratio = paper_size_ratio;
    params.update_factor = spec.update_factor;
    params.seed = spec.seed;
    return std::make_unique<PaperEnvironment<Dim>>(params);
}

std::unique_ptr<Scene<3>> make_sparse_scene(const SceneSpec& spec) {
    workload::EnvironmentParams params;
    params.box_count = spec.boxes;
    params.cube_side = sparse_cube_side;
    params.size_ratio = sparse_size_ratio;
    params.update_factor = spec.update_factor;
    params.seed = spec.seed;
    return std::make_unique<PaperEnvironment<3>>(params);
}

template std::unique_ptr<Scene<2>> make_paper_scene<2>(const SceneSpec&);
template std::unique_ptr<Scene<3>> make_paper_scene<3>(const SceneSpec&);

}  // namespace smb::bench
