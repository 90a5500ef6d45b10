// SPDX-License-Identifier: MIT
#pragma once
// A Detector's filtered detection split by interaction classes (interaction_classes.hpp). Where
// the filters make two classes or more, each class whose boxes can pair within is gathered into
// an array of its own and detected by a detection engine of its own (engine/detection_engine.hpp),
// whose persistent cuts then follow that class from call to call. Two layers that ignore each other cost their two
// detections, not one detection of all their boxes in which the pairs across the layers are
// found and dropped. The pairs still pass through the filtered sink (the bits, the static flags,
// the predicate), which maps them back to the caller's indices.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/pair_output.hpp"
#include "engine/detection_engine.hpp"
#include "filters/class_members.hpp"
#include "filters/filtered_sink.hpp"
#include "filters/interaction_classes.hpp"
#include "smb/box.hpp"
#include "smb/detector.hpp"
#include "smb/filter.hpp"
#include "smb/held_precision.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class DetectorClasses {
public:
    /// Detects `boxes` (already checked) class by class, handing the pairs that pass `filters`
    /// to `sink`, and adds the classes' work to `stats`; returns false, having detected nothing
    /// and released the classes' detectors, where the filters make fewer than two classes.
    bool detect(std::span<const Box<Real, Dim>> boxes, const DetectFilters& filters, const PairSink& sink,
                const DetectorSettings& settings, DetectStats& stats, DetectProfile& profile) {
        split_ = false;
        if (filters.filters.empty() || !follow(filters.filters)) {
            clear();
            return false;
        }
        split_ = true;
        std::size_t reported = 0;
        for (std::size_t c = 0; c < parts_.size(); ++c) {
            Part& part = parts_[c];
            const std::span<const std::uint32_t> members = members_.members(c);
            if (members.empty()) {
                part.engine.reset();
                std::vector<Box<Real, Dim>>().swap(part.boxes);
                continue;
            }
            part.boxes.resize(members.size());
            for (std::size_t k = 0; k < members.size(); ++k) part.boxes[k] = boxes[members[k]];
            if (!part.engine) part.engine = std::make_unique<DetectionEngine<Real, Dim>>();
            FilteredSink filtered(filters, sink, settings.pair_chunk_size, members, !classes_.all_pass_within(c));
            const PairSink filtered_sink(std::ref(filtered));
            std::size_t passed = 0;  // FilteredSink counts the pairs that pass the filters
            PairOutput output{chunk_, settings.pair_chunk_size, filtered_sink, passed};
            part.engine->detect({part.boxes, {}, nullptr, true}, settings, settings.skin, output, stats, profile);
            output.flush();
            reported += filtered.finish();
        }
        stats.pairs = reported;
        return true;
    }

    /// Whether the last detection was split.
    [[nodiscard]] bool split() const noexcept { return split_; }
    /// Doubles where any class held doubles; none where no class was detected.
    [[nodiscard]] HeldPrecision precision() const noexcept {
        HeldPrecision held = HeldPrecision::none;
        for (const Part& part : parts_) {
            if (!part.engine) continue;
            const HeldPrecision own = part.engine->precision();
            if (own == HeldPrecision::doubles) return own;
            if (own != HeldPrecision::none) held = own;
        }
        return held;
    }
    [[nodiscard]] std::size_t retested() const noexcept {
        std::size_t n = 0;
        for (const Part& part : parts_) n += part.engine ? part.engine->retested() : 0;
        return n;
    }

    void clear() {
        classes_.clear();
        std::vector<Part>().swap(parts_);
        std::vector<Pair>().swap(chunk_);
        members_.clear();
        split_ = false;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        std::size_t bytes = classes_.bytes_held() + parts_.capacity() * sizeof(Part) + members_.bytes_held() +
                            chunk_.capacity() * sizeof(Pair);
        for (const Part& part : parts_) {
            bytes += part.boxes.capacity() * sizeof(Box<Real, Dim>);
            if (part.engine) bytes += sizeof(DetectionEngine<Real, Dim>) + part.engine->bytes_held();
        }
        return bytes;
    }

private:
    /// One class, its members kept in class_members.hpp's order.
    struct Part {
        std::unique_ptr<DetectionEngine<Real, Dim>> engine;
        std::vector<Box<Real, Dim>> boxes;  // box of members(c)[k] at k
    };

    /// Brings the classes and their members to `filters`, the caller's index i being the box
    /// it was at the last call (the Detector's rule for its persistent cuts). Returns false where
    /// the filters make fewer than two classes.
    bool follow(std::span<const Filter> filters) {
        for (const Filter& f : filters) {
            if (filter_interacts(f) && !classes_.knows(f)) {
                rebuild(filters);
                break;
            }
        }
        if (classes_.count() < 2) return false;
        members_.resize(filters.size());  // indices past the array's end have left it
        for (std::size_t i = 0; i < filters.size(); ++i) {
            const Filter& f = filters[i];
            std::uint8_t now = ClassMembers::kNone;
            if (filter_interacts(f)) {
                const std::size_t c = classes_.class_of(f);
                if (classes_.pairs_within(c)) now = static_cast<std::uint8_t>(c);
            }
            members_.move(i, now);
        }
        return true;
    }

    /// New classes from the filters' values, every member gone from them.
    void rebuild(std::span<const Filter> filters) {
        classes_.build(filters.size(), [&](std::size_t i) { return filters[i]; });
        parts_.clear();
        parts_.resize(classes_.count());
        members_.reset(classes_.count());
    }

    InteractionClasses classes_;
    std::vector<Part> parts_;
    ClassMembers members_;     // the caller's indices by class
    std::vector<Pair> chunk_;  // the classes' pairs on their way to the filters
    bool split_ = false;
};

}  // namespace smb::detail
