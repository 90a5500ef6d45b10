// SPDX-License-Identifier: MIT
#pragma once
// A Detector's filters, applied to the pairs of indices its detection of the caller's whole
// array hands over (where every box can pair and the filters make one class, or only static
// flags and a predicate are given; class_detections.hpp detects the others): the chunks of the
// detection pass through here, and the pairs that pass the bits, the static flags and the
// predicate go on to the caller's sink in chunks of their own. The detection itself is the
// Detector's, unchanged, and so are its skin's candidates; a filtered pair costs one test here.

#include <cstddef>
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

class FilteredSink {
public:
    FilteredSink(const DetectFilters& filters, const PairSink& sink, std::size_t chunk_size)
        : filters_(filters.filters),
          rules_{filters.statics, filters.predicate ? &filters.predicate : nullptr},
          sink_(sink),
          chunk_size_(chunk_size) {
        kept_.reserve(chunk_size_);
    }

    void operator()(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) {
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
    std::vector<Pair> kept_;
    std::size_t passed_ = 0;
};

}  // namespace smb::detail
