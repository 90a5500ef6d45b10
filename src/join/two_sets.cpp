// SPDX-License-Identifier: MIT
// The two-set find_overlapping_pairs: the boxes that could meet the other set (set_cull.hpp)
// are detected together as one set, and only the pairs with one end in each set are kept.
// Reusing the one-set detection keeps a single exact, tested engine (precision, huge boxes,
// threads); its cost is the pairs within each set, which the cull keeps small where one set is
// much smaller than the other or lies in a thin layer of it (docs/two-sets.md has the numbers).

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "core/invalid_box.hpp"
#include "instantiations.hpp"
#include "join/set_cull.hpp"
#include "smb/detector.hpp"
#include "smb/join.hpp"
#include "smb/world.hpp"

namespace smb {

namespace {

template <std::floating_point Real, int Dim>
void check_boxes(std::span<const Box<Real, Dim>> boxes, const char* which) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!is_valid(boxes[i]))
            throw InvalidBoxError(std::string("find_overlapping_pairs: in the ") + which + " set, " +
                                  detail::describe_invalid_box(i, boxes[i]));
    }
}

/// Every pair of `boxes` (box i under id i) to `sink`: a Detector, which needs no ids and holds
/// about half a World's memory, unless the settings ask for the paper's lists, which only a
/// World has.
template <std::floating_point Real, int Dim>
void detect_union(std::span<const Box<Real, Dim>> boxes, const WorldSettings& settings, const PairSink& sink) {
    if (settings.pipeline == Pipeline::paper_lists) {
        World<Real, Dim> world(settings);
        world.assign(boxes);
        world.detect(sink);
        return;
    }
    DetectorSettings detector_settings;
    static_cast<DetectionSettings&>(detector_settings) = settings;
    Detector<Real, Dim> detector(detector_settings);
    detector.detect(boxes, sink);
}

}  // namespace

template <std::floating_point Real, int Dim>
std::vector<Pair> find_overlapping_pairs(std::span<const Box<Real, Dim>> first, std::span<const Box<Real, Dim>> second,
                                         const WorldSettings& settings) {
    check_boxes(first, "first");
    check_boxes(second, "second");
    const detail::KeptBoxes kept = detail::SetCull<Real, Dim>::keep(first, second);
    std::vector<Pair> pairs;
    if (kept.first.empty() || kept.second.empty()) {
        // Nothing to detect, but the settings are checked as a detection would check them.
        detect_union<Real, Dim>({}, settings, [](std::span<const Pair>) {});
        return pairs;
    }

    // A set the filters left nearly whole is detected whole: its boxes keep their own indices,
    // where a lookup per pair (a cache miss each, on millions of pairs) would cost more than
    // the few boxes saved. Exact all the same: every box that overlaps a box of the other set
    // was kept, and the detection reports only boxes that overlap.
    const bool whole_first = kept.first.size() * 8 > first.size() * 7;
    const bool whole_second = kept.second.size() * 8 > second.size() * 7;
    std::vector<Box<Real, Dim>> both;
    both.reserve((whole_first ? first.size() : kept.first.size()) +
                 (whole_second ? second.size() : kept.second.size()));
    if (whole_first) {
        both.insert(both.end(), first.begin(), first.end());
    } else {
        for (const std::size_t i : kept.first) both.push_back(first[i]);
    }
    const std::size_t split = both.size();
    if (whole_second) {
        both.insert(both.end(), second.begin(), second.end());
    } else {
        for (const std::size_t j : kept.second) both.push_back(second[j]);
    }

    detect_union<Real, Dim>(both, settings, [&](std::span<const Pair> chunk) {
        for (const Pair& pair : chunk) {
            // a < b always, so a pair across the sets has a before the split and b after it.
            if (pair.a >= split || pair.b < split) continue;
            if (pairs.size() >= settings.max_pairs_held) {
                throw PairLimitError("find_overlapping_pairs: more than " + std::to_string(settings.max_pairs_held) +
                                     " pairs between the two sets (WorldSettings::max_pairs_held)");
            }
            const std::size_t b = pair.b - split;
            pairs.push_back({whole_first ? pair.a : kept.first[pair.a], whole_second ? b : kept.second[b]});
        }
    });
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

#define SMB_INSTANTIATE(Real, Dim)                                \
    template std::vector<Pair> find_overlapping_pairs<Real, Dim>( \
        std::span<const Box<Real, Dim>>, std::span<const Box<Real, Dim>>, const WorldSettings&);
SMB_FOR_EACH_BOX_TYPE(SMB_INSTANTIATE)
#undef SMB_INSTANTIATE

}  // namespace smb
