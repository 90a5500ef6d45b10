// SPDX-License-Identifier: MIT
#pragma once
// detect(..., std::vector<Pair>&) of World and Detector: the pairs of one detection collected
// into the caller's vector, which keeps its old contents if the detection throws.

#include <cstddef>
#include <functional>
#include <vector>

#include "core/pair_output.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// Runs `fill` (which appends to `items` and returns a result), then leaves in `items` exactly
/// what it appended. The old contents stay in front until it succeeded, so that a throw (an
/// invalid box, the pair limit, an allocation) leaves them as they were; capacity a failed call
/// added is given back (past a pair limit it may be gigabytes). An empty vector costs nothing.
template <class Item, class Fill>
auto replace_on_success(std::vector<Item>& items, Fill&& fill) {
    const std::size_t kept = items.size();
    const std::size_t capacity = items.capacity();
    try {
        auto result = fill();
        items.erase(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(kept));
        return result;
    } catch (...) {
        items.resize(kept);
        if (items.capacity() > capacity) items.shrink_to_fit();
        throw;
    }
}

/// Runs `detect` (a callable taking a PairSink) and leaves in `pairs` exactly the pairs it
/// reported, all or nothing (replace_on_success()).
template <class Detect>
DetectStats collect_pairs(std::vector<Pair>& pairs, std::size_t limit, const char* limit_name,
                          const char* streaming_call, Detect&& detect) {
    const PairAppender appender{pairs, pairs.size(), limit, limit_name, streaming_call};
    return replace_on_success(pairs, [&] { return detect(PairSink(std::cref(appender))); });
}

}  // namespace smb::detail
