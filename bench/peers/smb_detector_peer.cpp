// SPDX-License-Identifier: MIT
#include "peers/peer_factories.hpp"

#include <sstream>

#include "smb/detector.hpp"
#include "smb/workload/swap_remove_mirror.hpp"

namespace smb::bench {
namespace {

/// smb::Detector as an array-based simulation would use it: its bodies in an array of its own,
/// where a body keeps its index (swap-remove: smb/workload/swap_remove_mirror.hpp). The detection
/// and turning the detector's indices into the scene's ids are measured; keeping the array is the
/// simulation's own work, done in prepare().
template <int Dim>
class SmbDetectorPeer final : public Peer<Dim> {
public:
    explicit SmbDetectorPeer(const DetectorSettings& settings) : detector_(settings) {}

    /// Untimed: a user's simulation keeps its bodies' boxes in its own array, moved in place and
    /// swap-removed, so the broad phase never copies them there; the scene hands over every box
    /// in id order, and the mirror turns that into such an array.
    void prepare(const SceneStep<Dim>& step) override {
        mirror_.follow(step.removed_ids, step.ids.subspan(step.first_inserted), step.ids, step.boxes);
    }

    void build(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override { find_pairs(pairs); }

    void step(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override {
        find_pairs(pairs);
        ++steps_;
        total_seconds_ += detector_.last_stats().total_seconds;
        bytes_held_ = detector_.bytes_held();
    }

    [[nodiscard]] std::string details_json() const override {
        if (steps_ == 0) return {};
        std::ostringstream json;
        json << "\"smb_detect_s\":" << total_seconds_ / static_cast<double>(steps_)
             << ",\"smb_bytes_held\":" << bytes_held_;
        return json.str();
    }

private:
    /// Timed: the detection over the array, and its indices turned into the scene's ids.
    void find_pairs(std::vector<Pair>& pairs) {
        pairs.clear();  // as every peer: detect() then has no old pairs to keep
        detector_.detect(mirror_.boxes(), pairs);
        for (Pair& pair : pairs) pair = ordered_pair(mirror_.id_at(pair.a), mirror_.id_at(pair.b));
    }

    workload::SwapRemoveMirror<BenchBox<Dim>> mirror_;
    Detector<float, Dim> detector_;
    std::size_t steps_ = 0;
    double total_seconds_ = 0;
    std::size_t bytes_held_ = 0;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_smb_detector_peer(const DetectorSettings& settings) {
    return std::make_unique<SmbDetectorPeer<Dim>>(settings);
}

template std::unique_ptr<Peer<2>> make_smb_detector_peer<2>(const DetectorSettings&);
template std::unique_ptr<Peer<3>> make_smb_detector_peer<3>(const DetectorSettings&);

}  // namespace smb::bench
