#pragma once
// What a Detector holds: its settings, and the persistent-cut pipeline over the caller's array,
// holding floats (double input shifted and rounded, held_box.hpp) or, where floats would not resolve the
// scene, a copy of the doubles (scene_bounds.hpp decides).

#include <chrono>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

#include "pair_output.hpp"
#include "persistent_cut_pipeline.hpp"
#include "scene_bounds.hpp"
#include "settings_check.hpp"
#include "skin_list.hpp"
#include "smb/detector.hpp"
#include "smb/errors.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class DetectorState {
public:
    explicit DetectorState(const WorldSettings& settings) : settings_(validated_settings(settings)) {
        if (settings_.pipeline != Pipeline::persistent_cuts)
            throw ArgumentError("Detector: WorldSettings::pipeline must be Pipeline::persistent_cuts");
    }
    DetectorState(const DetectorState&) = delete;
    DetectorState& operator=(const DetectorState&) = delete;

    const WorldSettings& settings() const noexcept { return settings_; }
    const DetectStats& last_stats() const noexcept { return stats_; }
    HeldPrecision last_precision() const noexcept { return precision_; }
    std::size_t last_retested_pairs() const noexcept { return retested_; }

    void clear() {
        exact_ = ExactPipeline();
        rounded_ = RoundedPipeline();
        skin_.clear();
        skin_pause_ = 0;
        retested_ = 0;
        std::vector<Pair>().swap(chunk_);
        judged_ = false;
        precision_ = HeldPrecision::none;
        stats_ = {};
    }

    DetectStats detect(std::span<const Box<Real, Dim>> boxes, const PairSink& sink) {
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        DetectStats stats;
        stats.boxes = boxes.size();
        SceneBounds<Real, Dim> bounds;
        if (!boxes.empty()) {
            bounds = checked_bounds(boxes);  // throws before any change
            if constexpr (kMayRound) choose_precision(boxes, bounds);
            else precision_ = HeldPrecision::floats;
        }
        stats.update_seconds = std::chrono::duration<double>(Clock::now() - start).count();

        PairOutput output{chunk_, settings_.pair_chunk_size, sink, stats.pairs};
        retested_ = 0;
        if (boxes.empty()) {
            exact_.forget_slots_from(0);
            exact_.detect(boxes, {}, settings_, output, stats);
            rounded_ = RoundedPipeline();
            skin_.clear();
            precision_ = HeldPrecision::none;
            judged_ = false;
        } else if (!detected_with_skin(boxes, bounds, output, stats)) {
            if (uses_rounded()) {
                rounded_.forget_slots_from(boxes.size());
                rounded_.set_scene_bounds(bounds.lo, bounds.hi);
                rounded_.detect(boxes, {}, settings_, output, stats);
                if constexpr (kMayRound) retested_ = rounded_.retested();
            } else {
                exact_.forget_slots_from(boxes.size());
                exact_.detect(boxes, {}, settings_, output, stats);
            }
        }
        output.flush();
        stats.bytes_held = bytes_held();
        stats.total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
        stats_ = stats;
        return stats;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return sizeof(*this) + exact_.bytes_held() + rounded_.bytes_held() + skin_.bytes_held() +
               chunk_.capacity() * sizeof(Pair);
    }

private:
    /// Double input may be held as floats; float input is held as it is.
    static constexpr bool kMayRound = !std::is_same_v<Real, float>;
    using ExactPipeline = PersistentCutPipeline<Real, Dim, Real>;
    using RoundedPipeline = std::conditional_t<kMayRound, PersistentCutPipeline<float, Dim, Real>, ExactPipeline>;

    /// With a skin, on floats (the input's own, or double input that floats resolve): the skin
    /// list detects, and the pipelines give their memory back when it (re)builds. When it steps
    /// aside (SkinList::detect()), the pipelines detect for kSkinPause detections.
    bool detected_with_skin(std::span<const Box<Real, Dim>> boxes, const SceneBounds<Real, Dim>& bounds,
                            PairOutput& output, DetectStats& stats) {
        if (settings_.skin == 0 || precision_ != HeldPrecision::floats) {
            skin_.clear();
            return false;
        }
        if (skin_pause_ > 0) {
            --skin_pause_;
            return false;
        }
        std::array<Real, Dim> origin{};
        if constexpr (kMayRound) origin = judgement_.origin;
        if (!skin_.detect(boxes, origin, bounds.lo, bounds.hi, settings_.skin, settings_, output, stats)) {
            skin_pause_ = kSkinPause;
            return false;
        }
        retested_ = skin_.retested();
        if (stats.skin_rebuilt) {  // a (re)build is the first skin detection after the pipelines' ones
            exact_ = ExactPipeline();
            rounded_ = RoundedPipeline();
            if constexpr (kMayRound) rounded_.set_origin(judgement_.origin);
        }
        return true;
    }

    [[nodiscard]] bool uses_rounded() const noexcept {
        return kMayRound && precision_ == HeldPrecision::floats;
    }

    /// Judges the scene again when it left the region of the last judgement, when the number of
    /// boxes moved by more than a quarter (the cut counts change then anyway), and every
    /// kJudgeEvery detections (a scene of points may have grown into boxes). A new origin forgets
    /// the cuts, so a scene still held as floats and still inside its region keeps its origin;
    /// switching gives the other pipeline's memory back.
    void choose_precision(std::span<const Box<Real, Dim>> boxes, const SceneBounds<Real, Dim>& bounds) {
        const std::size_t n = boxes.size();
        const bool inside = judged_ && bounds.within(judgement_.region);
        const bool stale = !inside || 4 * n > 5 * judged_boxes_ || 5 * n < 4 * judged_boxes_ ||
                           ++since_judged_ >= kJudgeEvery;
        if (!stale) return;
        FloatResolution<Real, Dim> judged = judge_float_resolution(boxes, bounds);
        judged_ = true;
        judged_boxes_ = n;
        since_judged_ = 0;
        if (judged.floats && precision_ == HeldPrecision::floats && inside) return;
        judgement_ = judged;
        if (judged.floats) {
            if constexpr (kMayRound) rounded_.set_origin(judged.origin);
            exact_ = ExactPipeline();
            precision_ = HeldPrecision::floats;
        } else {
            rounded_ = RoundedPipeline();
            precision_ = HeldPrecision::exact;
        }
    }

    static constexpr std::size_t kJudgeEvery = 64;
    static constexpr std::size_t kSkinPause = 64;

    WorldSettings settings_;
    ExactPipeline exact_;
    RoundedPipeline rounded_;
    SkinList<Real, Dim> skin_;
    std::size_t skin_pause_ = 0;
    std::size_t retested_ = 0;
    FloatResolution<Real, Dim> judgement_;
    bool judged_ = false;
    std::size_t judged_boxes_ = 0;
    std::size_t since_judged_ = 0;
    HeldPrecision precision_ = HeldPrecision::none;
    DetectStats stats_;
    std::vector<Pair> chunk_;
};

}  // namespace smb::detail
