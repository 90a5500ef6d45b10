// SPDX-License-Identifier: MIT
#include "peers/peer_factories.hpp"

#include <span>
#include <sstream>
#include <type_traits>

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
        total_seconds_ = 0;
    }

    void step(const SceneStep<Dim>& step, std::vector<Pair>& pairs) override {
        if (!step.removed_ids.empty()) world_.remove(step.removed_ids);
        const std::span<const Box<Real, Dim>> boxes = boxes_of(step);
        world_.update(step.ids.first(step.first_inserted), boxes.first(step.first_inserted));
        if (step.inserted_count() > 0)
            world_.insert(step.ids.subspan(step.first_inserted), boxes.subspan(step.first_inserted));
        pairs.clear();  // as every peer: detect() then has no old pairs to keep
        const DetectStats stats = world_.detect(pairs);
        const DetectProfile& profile = world_.last_profile();
        ++steps_;
        phases_.update_seconds += profile.update_seconds;
        phases_.scan_seconds += profile.scan_seconds;
        phases_.quantile_seconds += profile.quantile_seconds;
        phases_.list_sort_seconds += profile.list_sort_seconds;
        phases_.cut_regroup_seconds += profile.cut_regroup_seconds;
        phases_.check_seconds += profile.check_seconds;
        phases_.copy_seconds += profile.copy_seconds;
        for (std::size_t level = 0; level < profile.level_seconds.size(); ++level)
            phases_.level_seconds[level] += profile.level_seconds[level];
        phases_.sort_moves += profile.sort_moves;
        phases_.cells = profile.cells;
        phases_.oversized_boxes = profile.oversized_boxes;
        total_seconds_ += stats.total_seconds;
        bytes_held_ = stats.bytes_held;
    }

    // Where detect() spends its time, averaged over the steps after the first.
    [[nodiscard]] std::string details_json() const override {
        if (steps_ == 0) return {};
        const double n = static_cast<double>(steps_);
        std::ostringstream json;
        json << "\"smb_update_s\":" << phases_.update_seconds / n << ",\"smb_scan_s\":" << phases_.scan_seconds / n
             << ",\"smb_quantile_s\":" << phases_.quantile_seconds / n
             << ",\"smb_list_sort_s\":" << phases_.list_sort_seconds / n
             << ",\"smb_cut_regroup_s\":" << phases_.cut_regroup_seconds / n
             << ",\"smb_check_s\":" << phases_.check_seconds / n << ",\"smb_copy_s\":" << phases_.copy_seconds / n
             << ",\"smb_level_s\":[" << phases_.level_seconds[0] / n << ',' << phases_.level_seconds[1] / n << ','
             << phases_.level_seconds[2] / n << "],\"smb_detect_s\":" << total_seconds_ / n
             << ",\"smb_sort_moves\":" << static_cast<double>(phases_.sort_moves) / n
             << ",\"smb_cells\":" << phases_.cells << ",\"smb_oversized\":" << phases_.oversized_boxes
             << ",\"smb_bytes_held\":" << bytes_held_;
        return json.str();
    }

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
    DetectProfile phases_;
    double total_seconds_ = 0;
    std::size_t bytes_held_ = 0;
    std::size_t steps_ = 0;
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
