// SPDX-License-Identifier: MIT
#include "peers/peer_factories.hpp"

#include "peers/smb_phases.hpp"
#include "smb/detector.hpp"
#include "smb/workload/swap_remove_mirror.hpp"

namespace smb::bench {
namespace {

/// smb::Detector as an array-based simulation would use it: its bodies in an array of its own,
/// where a body keeps its index (swap-remove: smb/workload/swap_remove_mirror.hpp). The detection
/// and turning the detector's indices into the scene's ids are measured; keeping the array is the
/// simulation's own work, done in prepare(). With `renumber_every` > 0 the simulation also
/// renumbers its bodies in the detector's suggested order (Detector::suggested_order()) after
/// the build and then every that many steps, timed with the detection that follows it.
template <int Dim>
class SmbDetectorPeer final : public Peer<Dim> {
public:
    // Profiled, for the phases of details_json(), as the World peer.
    SmbDetectorPeer(DetectorSettings settings, std::size_t renumber_every)
        : detector_(profiled(settings)), renumber_every_(renumber_every) {}

    /// Untimed: a user's simulation keeps its bodies' boxes in its own array, moved in place and
    /// swap-removed, so the broad phase never copies them there; the scene hands over every box
    /// in id order, and the mirror turns that into such an array.
    void prepare(const SceneStep<Dim>& step) override {
        mirror_.follow(step.removed_ids, step.ids.subspan(step.first_inserted), step.ids, step.boxes);
    }

    void build(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override {
        find_pairs(pairs);
        if (renumber_every_ > 0) renumber();
    }

    void step(const SceneStep<Dim>& /*step*/, std::vector<Pair>& pairs) override {
        find_pairs(pairs);
        phases_.add(detector_.last_profile(), detector_.last_stats());
        ++steps_;
        if (renumber_every_ > 0 && steps_ % renumber_every_ == 0) renumber();
    }

    [[nodiscard]] std::string details_json() const override { return phases_.json(); }

private:
    static DetectorSettings profiled(DetectorSettings settings) {
        settings.profile = true;
        return settings;
    }

    /// Timed: the detection over the array, and its indices turned into the scene's ids.
    void find_pairs(std::vector<Pair>& pairs) {
        pairs.clear();  // as every peer: detect() then has no old pairs to keep
        detector_.detect(mirror_.boxes(), pairs);
        for (Pair& pair : pairs) pair = ordered_pair(mirror_.id_at(pair.a), mirror_.id_at(pair.b));
    }

    /// Timed with the detection before it: the boxes and their ids moved to the suggested order.
    void renumber() {
        const std::span<const std::uint32_t> order = detector_.suggested_order();
        if (order.size() != mirror_.boxes().size()) return;
        mirror_.renumber(order);
        detector_.follow_suggested_order();
    }

    workload::SwapRemoveMirror<BenchBox<Dim>> mirror_;
    Detector<float, Dim> detector_;
    std::size_t renumber_every_ = 0;
    std::size_t steps_ = 0;
    SmbPhases phases_;
};

}  // namespace

template <int Dim>
std::unique_ptr<Peer<Dim>> make_smb_detector_peer(const DetectorSettings& settings, std::size_t renumber_every) {
    return std::make_unique<SmbDetectorPeer<Dim>>(settings, renumber_every);
}

template std::unique_ptr<Peer<2>> make_smb_detector_peer<2>(const DetectorSettings&, std::size_t);
template std::unique_ptr<Peer<3>> make_smb_detector_peer<3>(const DetectorSettings&, std::size_t);

}  // namespace smb::bench
