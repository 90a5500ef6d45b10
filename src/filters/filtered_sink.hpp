// SPDX-License-Identifier: MIT
#pragma once
// A Detector's filters, applied to the pairs of indices its detection hands over: the chunks
// of the detection pass through here, and the pairs that pass the bits, the static flags and
// the predicate go on to the caller's sink in chunks of their own. The detection itself is the
// Detector's, unchanged; a filtered pair costs one test here. Boxes whose category or mask is 0
// are left out of the detection (gather_interacting()): the detection then runs over the others,
// gathered in their order, and the sink maps its indices back.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/pair_output.hpp"
#include "filters/filtered_report.hpp"
#include "smb/errors.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// Throws ArgumentError unless each span of `filters` is empty or holds one entry per box.
inline void check_filter_lengths(const DetectFilters& filters, std::size_t boxes) {
    auto check = [&](std::size_t size, const char* what) {
        if (size != 0 && size != boxes)
            throw ArgumentError(std::string("detect: ") + std::to_string(size) + " " + what + " for " +
                                std::to_string(boxes) + " boxes (give none, or one per box)");
    };
    check(filters.filters.size(), "filters");
    check(filters.statics.size(), "static flags");
}

[[nodiscard]] inline bool filters_in_use(const DetectFilters& filters) noexcept {
    return !filters.filters.empty() || !filters.statics.empty() || static_cast<bool>(filters.predicate);
}

/// Gathers the boxes that can pair with something into `gathered`, and their indices into
/// `origin`, in order; returns false (and gathers nothing) when every box can.
template <class Box>
bool gather_interacting(std::span<const Box> boxes, std::span<const Filter> filters, std::vector<Box>& gathered,
                        std::vector<std::uint32_t>& origin) {
    gathered.clear();
    origin.clear();
    bool all = true;
    for (const Filter& f : filters) all = all && filter_interacts(f);
    if (all) return false;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (!filter_interacts(filters[i])) continue;
        gathered.push_back(boxes[i]);
        origin.push_back(static_cast<std::uint32_t>(i));
    }
    return true;
}

class FilteredSink {
public:
    /// `origin` empty: the detection ran over the caller's array; otherwise over the boxes
    /// gathered from it, index i being the caller's origin[i] (in any order).
    FilteredSink(const DetectFilters& filters, const PairSink& sink, std::size_t chunk_size,
                 std::span<const std::uint32_t> origin)
        : filters_(filters.filters),
          rules_{filters.statics, filters.predicate ? &filters.predicate : nullptr},
          sink_(sink),
          chunk_size_(chunk_size),
          origin_(origin) {
        kept_.reserve(chunk_size_);
    }

    void operator()(std::span<const Pair> pairs) {
        for (Pair p : pairs) {
            if (!origin_.empty()) p = ordered_pair(origin_[p.a], origin_[p.b]);
            if (!passes(p)) continue;
            kept_.push_back(p);
            if (kept_.size() == chunk_size_) send();
        }
    }

    /// Hands over what is left; returns the number of pairs that passed.
    std::size_t finish() {
        if (!kept_.empty()) send();
        return passed_;
    }

private:
    [[nodiscard]] bool passes(const Pair& p) const {
        return (filters_.empty() || filters_pass(filters_[p.a], filters_[p.b])) && rules_.pass(p.a, p.b);
    }

    void send() {
        passed_ += kept_.size();
        sink_(std::span<const Pair>(kept_));
        kept_.clear();
    }

    std::span<const Filter> filters_;
    PairRules rules_;
    const PairSink& sink_;
    std::size_t chunk_size_;
    std::span<const std::uint32_t> origin_;
    std::vector<Pair> kept_;
    std::size_t passed_ = 0;
};

}  // namespace smb::detail
