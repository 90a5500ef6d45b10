// SPDX-License-Identifier: MIT
#pragma once
// The filter layer of both front doors: boxes split by interaction classes
// (interaction_classes.hpp) and, where there is more than one class, detected class by class.
// Each class that can pair within has its own array of boxes in the order of its members
// (class_members.hpp) and its own detection engine, whose persistent cuts then follow that class
// from one detection to the next; its pairs pass through the filters (filtered_report.hpp).
//
// The boxes are known by position: a World places the positions of its list of moving boxes as
// they change (world_filters.hpp), a Detector brings the caller's indices to their filters at
// every call (follow()). A World detects by classes where there are two classes or more; a
// Detector where there are two, or where some boxes are left out of its one class (otherwise it
// detects the caller's array itself, and offers the skin's candidates).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/detection_engine.hpp"
#include "filters/class_members.hpp"
#include "filters/filtered_report.hpp"
#include "filters/interaction_classes.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// Boxes gathered for one detection engine, index k reported under its id in info[k]: a class
/// of boxes, or all the moving boxes of a World whose filters make one class.
template <std::floating_point Real, int Dim>
struct GatheredDetection {
    DetectionEngine<Real, Dim> engine;
    std::vector<Box<Real, Dim>> boxes;
    std::vector<IdFilter> info;  // index k's id and filter
    std::vector<BoxId> keys;     // index k's key for the pipeline, when packed
    bool packed = true;

    template <class BoxOf, class InfoOf>
    void gather(std::size_t n, BoxOf&& box_of, InfoOf&& info_of) {
        boxes.resize(n);
        info.resize(n);
        keys.resize(n);
        packed = true;
        for (std::size_t k = 0; k < n; ++k) {
            info[k] = info_of(k);
            boxes[k] = box_of(k);
            keys[k] = packed_key(info[k].id, info[k].filter);
            packed = packed && packable(info[k].id, info[k].filter);
        }
    }

    /// Reports the pairs of the boxes that pass the filters and `rules`: by the packed keys
    /// where every box has one, otherwise by index into `info`.
    template <class Output>
    void detect(const DetectionSettings& settings, double skin, Output& output, const PairRules& rules,
                DetectStats& stats, DetectProfile& profile) {
        if (boxes.empty()) {
            engine.clear();
        } else if (packed) {
            PackedFilterReport<Output> report(output, rules);
            engine.detect({boxes, keys, nullptr, true}, settings, skin, report, stats, profile);
        } else {
            FilteredReport<Output> report(output, info, rules);
            engine.detect({boxes, {}, nullptr, true}, settings, skin, report, stats, profile);
        }
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return engine.bytes_held() + boxes.capacity() * sizeof(Box<Real, Dim>) + info.capacity() * sizeof(IdFilter) +
               keys.capacity() * sizeof(BoxId);
    }
};

template <std::floating_point Real, int Dim>
class ClassDetections {
public:
    /// The classes hold their members and engines from `least` classes on.
    explicit ClassDetections(std::size_t least) : least_(least) {}

    [[nodiscard]] const InteractionClasses& classes() const noexcept { return classes_; }
    /// Whether the classes hold their members and engines: the boxes may be detected by classes.
    [[nodiscard]] bool split() const noexcept { return classes_.count() >= least_; }
    /// Positions in a class: all of them where every box can pair with something.
    [[nodiscard]] std::size_t placed() const noexcept {
        std::size_t n = 0;
        for (std::size_t c = 0; c < detections_.size(); ++c) n += members_.members(c).size();
        return n;
    }

    /// New classes from the values filter_of(p) of positions [0, n), every position placed in
    /// its class; the classes' engines start afresh.
    template <class FilterOf>
    void build(std::size_t n, FilterOf&& filter_of) {
        classes_.build(n, filter_of);
        std::vector<Detection>().swap(detections_);
        if (!split()) {
            members_.clear();
            return;
        }
        detections_.resize(classes_.count());
        members_.reset(classes_.count());
        for (std::size_t p = 0; p < n; ++p) place(p, filter_of(p));
    }

    /// Brings the classes to `filters`, position i being the box it was at the last call (the
    /// Detector's rule for its persistent cuts); returns split().
    bool follow(std::span<const Filter> filters) {
        if (split()) members_.resize(filters.size());  // indices past the array's end have left it
        for (std::size_t i = 0; i < filters.size(); ++i) {
            const std::uint8_t c = class_of(filters[i]);
            if (c == kUnknown) {
                build(filters.size(), [&](std::size_t k) { return filters[k]; });
                return split();
            }
            if (split()) members_.move(i, c);
        }
        return split();
    }

    /// The box at position p (held, or the next position) now has filter f. A value the classes
    /// do not know places it in none: the classes are to be built again before the next
    /// detection.
    void place(std::size_t p, const Filter& f) {
        if (!split()) return;
        const std::uint8_t c = class_of(f);
        members_.move(p, c == kUnknown ? ClassMembers::kNone : c);
    }
    /// The positions were swap-removed at p: the box at `last` (the last) now sits at p.
    void swap_remove(std::size_t p, std::size_t last) {
        if (split()) members_.swap_remove(p, last);
    }

    /// Gathers each class's boxes, in the order of its members: box_of(p) and info_of(p) (its
    /// reported id and its filter) for the box at position p.
    template <class BoxOf, class InfoOf>
    void gather(BoxOf&& box_of, InfoOf&& info_of) {
        for (std::size_t c = 0; c < detections_.size(); ++c) {
            const std::span<const std::uint32_t> members = members_.members(c);
            detections_[c].gather(
                classes_.pairs_within(c) ? members.size() : 0, [&](std::size_t k) { return box_of(members[k]); },
                [&](std::size_t k) { return info_of(members[k]); });
        }
    }

    /// Reports the pairs of every class that pass `rules`. The stats of the passes add up over
    /// the classes.
    template <class Output>
    void detect(const DetectionSettings& settings, double skin, Output& output, const PairRules& rules,
                DetectStats& stats, DetectProfile& profile) {
        for (Detection& c : detections_) c.detect(settings, skin, output, rules, stats, profile);
    }

    /// Doubles where any class holds doubles; none where no class was detected.
    [[nodiscard]] HeldPrecision precision() const noexcept {
        HeldPrecision held = HeldPrecision::none;
        for (const Detection& c : detections_) {
            if (c.engine.precision() == HeldPrecision::doubles) return HeldPrecision::doubles;
            if (c.engine.precision() != HeldPrecision::none) held = c.engine.precision();
        }
        return held;
    }
    [[nodiscard]] std::size_t retested() const noexcept {
        std::size_t n = 0;
        for (const Detection& c : detections_) n += c.engine.retested();
        return n;
    }

    /// Forgets the classes, their members and their engines.
    void clear() { *this = ClassDetections(least_); }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = classes_.bytes_held() + detections_.capacity() * sizeof(Detection) + members_.bytes_held();
        for (const Detection& c : detections_) bytes += c.bytes_held();
        return bytes;
    }

private:
    using Detection = GatheredDetection<Real, Dim>;
    static constexpr std::uint8_t kUnknown = InteractionClasses::kUnknown;
    static_assert(ClassMembers::kNone != kUnknown);

    /// The class of a box with filter f: ClassMembers::kNone where it pairs with nothing,
    /// kUnknown where the classes do not know its value.
    [[nodiscard]] std::uint8_t class_of(const Filter& f) const noexcept {
        return filter_interacts(f) ? classes_.class_of(f) : ClassMembers::kNone;
    }

    std::size_t least_;
    InteractionClasses classes_;
    std::vector<Detection> detections_;  // one per class where split()
    ClassMembers members_;               // the positions by class, where split()
};

}  // namespace smb::detail
