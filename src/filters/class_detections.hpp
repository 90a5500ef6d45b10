// SPDX-License-Identifier: MIT
#pragma once
// The moving boxes of a World's filtered path detected class by class (interaction_classes.hpp),
// where there is more than one class: each class that can pair within has its own array of boxes,
// its own persistent-cut pipeline. Each class keeps its members as the list of moving boxes
// keeps its boxes (a box that leaves is swap-removed, a box that joins is appended), so that from
// one detection to the next a pipeline sees the same box at the same index (an order derived
// from the list would shift every index past a removed box, and with a few removals a step the
// pipelines would find no box where they left it).
// A class whose values pass with none of its own is not gathered at all.
// Each array is detected by a detection engine of its own (engine/detection_engine.hpp), its
// pairs passing through the filters (filtered_report.hpp) on their way out.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/box_store.hpp"
#include "engine/detection_engine.hpp"
#include "filters/class_stats.hpp"
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
                     DetectStats& stats) {
    if (packed) {
        PackedFilterReport<Output> report(output, predicate);
        engine.detect({boxes, keys, nullptr, true}, settings, skin, report, stats);
    } else {
        FilteredReport<Output> report(output, info, predicate);
        engine.detect({boxes, {}, nullptr, true}, settings, skin, report, stats);
    }
}

template <std::floating_point Real, int Dim>
class ClassDetections {
public:
    using box_type = Box<Real, Dim>;

    /// Forgets every class's pipeline, boxes and members, keeping room for `count` classes.
    void reset(std::size_t count) {
        classes_.clear();
        classes_.resize(count);
        class_of_.clear();
        index_.clear();
    }
    void clear() {
        std::vector<ClassDetection>().swap(classes_);
        std::vector<std::uint8_t>().swap(class_of_);
        std::vector<std::uint32_t>().swap(index_);
    }

    /// The moving box at `position` (the next position of the list) is of class c: it takes the
    /// next index of its class.
    void join(Slot position, std::size_t c) {
        if (index_.size() <= position) {
            index_.resize(position + 1);
            class_of_.resize(position + 1);
        }
        std::vector<Slot>& members = classes_[c].members;
        class_of_[position] = static_cast<std::uint8_t>(c);
        index_[position] = static_cast<std::uint32_t>(members.size());
        members.push_back(position);
    }
    /// The box at `position` is now of class c.
    void change(Slot position, std::size_t c) {
        if (class_of_[position] == c) return;
        leave(position);
        join_again(position, c);
    }
    /// The list swap-removed position p: the box at `last` now sits at p.
    void swap_remove(Slot p, Slot last) {
        leave(p);
        if (p != last) {
            const std::uint8_t c = class_of_[last];
            const std::uint32_t k = index_[last];
            classes_[c].members[k] = p;
            class_of_[p] = c;
            index_[p] = k;
        }
        class_of_.pop_back();
        index_.pop_back();
    }

    /// Gathers each class's boxes, in the order of its members: the positions of `moving`,
    /// slots of `store` with filters[slot].
    void gather(const BoxStore<Real, Dim>& store, std::span<const Slot> moving, std::span<const Filter> filters,
                const InteractionClasses& classes) {
        for (std::size_t c = 0; c < classes_.size(); ++c) {
            ClassDetection& detection = classes_[c];
            const std::size_t n = classes.pairs_within(c) ? detection.members.size() : 0;
            detection.boxes.resize(n);
            detection.info.resize(n);
            detection.keys.resize(n);
            detection.packed = true;
            for (std::size_t k = 0; k < n; ++k) {
                const Slot s = moving[detection.members[k]];
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
                DetectStats& stats) {
        for (ClassDetection& c : classes_) {
            if (c.boxes.empty()) {
                c.engine.clear();
                continue;
            }
            DetectStats part;
            detect_gathered<Real, Dim>(c.engine, c.boxes, c.keys, c.info, c.packed, settings, skin, output, predicate,
                                       part);
            add_class_stats(stats, part);
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
        std::size_t bytes = classes_.capacity() * sizeof(ClassDetection) + class_of_.capacity() +
                            index_.capacity() * sizeof(std::uint32_t);
        for (const ClassDetection& c : classes_) {
            bytes += c.members.capacity() * sizeof(Slot) + c.engine.bytes_held() +
                     c.boxes.capacity() * sizeof(box_type) + c.info.capacity() * sizeof(IdFilter) +
                     c.keys.capacity() * sizeof(BoxId);
        }
        return bytes;
    }

private:
    struct ClassDetection {
        std::vector<Slot> members;  // positions in the list of moving boxes, each at its index
        DetectionEngine<Real, Dim> engine;
        std::vector<box_type> boxes;
        std::vector<IdFilter> info;  // index i's id and filter
        std::vector<BoxId> keys;     // index i's key for the pipeline, when packed
        bool packed = true;
    };

    /// Position p of the list of moving boxes leaves its class (swap-removed there).
    void leave(Slot p) {
        std::vector<Slot>& members = classes_[class_of_[p]].members;
        const std::uint32_t k = index_[p];
        const Slot moved = members.back();
        members[k] = moved;
        index_[moved] = k;
        members.pop_back();
    }
    /// As join(), for a position already held.
    void join_again(Slot p, std::size_t c) {
        std::vector<Slot>& members = classes_[c].members;
        class_of_[p] = static_cast<std::uint8_t>(c);
        index_[p] = static_cast<std::uint32_t>(members.size());
        members.push_back(p);
    }

    std::vector<ClassDetection> classes_;
    // Per position of the list of moving boxes: its class and its index there.
    std::vector<std::uint8_t> class_of_;
    std::vector<std::uint32_t> index_;
};

}  // namespace smb::detail
