// SPDX-License-Identifier: MIT
#pragma once
// The moving boxes of a World's filtered path detected class by class (interaction_classes.hpp),
// where there is more than one class: each class that can pair within has its own array of boxes
// in the order of its members (class_members.hpp) and its own detection engine
// (engine/detection_engine.hpp), its pairs passing through the filters (filtered_report.hpp) on
// their way out. A class whose values pass with none of its own is not gathered at all.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/box_store.hpp"
#include "engine/detection_engine.hpp"
#include "filters/class_members.hpp"
#include "filters/filtered_report.hpp"
#include "filters/interaction_classes.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/settings.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// Detects `boxes` (valid) with `engine`, each pair passing the filters and the predicate (if
/// not null) on its way to `output`: by the boxes' packed keys where `packed`, otherwise by
/// index into `info`.
template <std::floating_point Real, int Dim, class Output>
void detect_gathered(DetectionEngine<Real, Dim>& engine, std::span<const Box<Real, Dim>> boxes,
                     std::span<const BoxId> keys, std::span<const IdFilter> info, bool packed,
                     const DetectionSettings& settings, double skin, Output& output, const PairPredicate* predicate,
                     DetectStats& stats, DetectProfile& profile) {
    if (packed) {
        PackedFilterReport<Output> report(output, predicate);
        engine.detect({boxes, keys, nullptr, true}, settings, skin, report, stats, profile);
    } else {
        FilteredReport<Output> report(output, info, predicate);
        engine.detect({boxes, {}, nullptr, true}, settings, skin, report, stats, profile);
    }
}

template <std::floating_point Real, int Dim>
class ClassDetections {
public:
    /// Forgets every class's pipeline, boxes and members, keeping room for `count` classes.
    void reset(std::size_t count) {
        classes_.clear();
        classes_.resize(count);
        members_.reset(count);
    }
    void clear() {
        std::vector<ClassDetection>().swap(classes_);
        members_.clear();
    }

    /// The moving box at `position` (held, or the next position of the list) is now of class c.
    void place(Slot position, std::size_t c) { members_.move(position, static_cast<std::uint8_t>(c)); }
    /// The list swap-removed position p: the box at `last` now sits at p.
    void swap_remove(Slot p, Slot last) { members_.swap_remove(p, last); }

    /// Gathers each class's boxes, in the order of its members: the positions of `moving`,
    /// slots of `store` with filters[slot].
    void gather(const BoxStore<Real, Dim>& store, std::span<const Slot> moving, std::span<const Filter> filters,
                const InteractionClasses& classes) {
        for (std::size_t c = 0; c < classes_.size(); ++c) {
            ClassDetection& detection = classes_[c];
            const std::span<const std::uint32_t> members = members_.members(c);
            const std::size_t n = classes.pairs_within(c) ? members.size() : 0;
            detection.boxes.resize(n);
            detection.info.resize(n);
            detection.keys.resize(n);
            detection.packed = true;
            for (std::size_t k = 0; k < n; ++k) {
                const Slot s = moving[members[k]];
                const IdFilter info{store.id_at(s), filters[s]};
                detection.boxes[k] = store.box_at(s);
                detection.info[k] = info;
                detection.keys[k] = packed_key(info.id, info.filter);
                detection.packed = detection.packed && packable(info.id, info.filter);
            }
        }
    }

    /// Reports the pairs of every class that passes, through the predicate if not null. The
    /// stats of the passes add up over the classes.
    template <class Output>
    void detect(const DetectionSettings& settings, double skin, Output& output, const PairPredicate* predicate,
                DetectStats& stats, DetectProfile& profile) {
        for (ClassDetection& c : classes_) {
            if (c.boxes.empty()) {
                c.engine.clear();
                continue;
            }
            detect_gathered<Real, Dim>(c.engine, c.boxes, c.keys, c.info, c.packed, settings, skin, output, predicate,
                                       stats, profile);
        }
    }

    /// Doubles where any class holds doubles; none where no class was detected.
    [[nodiscard]] HeldPrecision precision() const noexcept {
        HeldPrecision held = HeldPrecision::none;
        for (const ClassDetection& c : classes_) {
            if (c.engine.precision() == HeldPrecision::doubles) return HeldPrecision::doubles;
            if (c.engine.precision() != HeldPrecision::none) held = c.engine.precision();
        }
        return held;
    }
    [[nodiscard]] std::size_t retested() const noexcept {
        std::size_t n = 0;
        for (const ClassDetection& c : classes_) n += c.engine.retested();
        return n;
    }
    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = classes_.capacity() * sizeof(ClassDetection) + members_.bytes_held();
        for (const ClassDetection& c : classes_) {
            bytes += c.engine.bytes_held() + c.boxes.capacity() * sizeof(Box<Real, Dim>) +
                     c.info.capacity() * sizeof(IdFilter) + c.keys.capacity() * sizeof(BoxId);
        }
        return bytes;
    }

private:
    struct ClassDetection {
        DetectionEngine<Real, Dim> engine;
        std::vector<Box<Real, Dim>> boxes;
        std::vector<IdFilter> info;  // index i's id and filter
        std::vector<BoxId> keys;     // index i's key for the pipeline, when packed
        bool packed = true;
    };

    std::vector<ClassDetection> classes_;
    ClassMembers members_;
};

}  // namespace smb::detail
