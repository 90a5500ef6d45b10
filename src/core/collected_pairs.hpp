// SPDX-License-Identifier: MIT
#pragma once
// detect(..., std::vector<Pair>&) of World and Detector: the pairs of one detection collected
// into the caller's vector, which keeps its old contents if the detection throws.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "smb/errors.hpp"
#include "smb/pair.hpp"
#include "smb/stats.hpp"

namespace smb::detail {

/// The sink that appends every chunk to `pairs` after the `kept` pairs it held before, and
/// throws PairLimitError past `limit` new pairs, naming `limit_name` (the settings field) and
/// `streaming_call` (the way to take any number of pairs). Handed over as std::cref(appender),
/// so that the PairSink holds a reference and allocates nothing on a detection.
struct PairAppender {
    std::vector<Pair>& pairs;
    std::size_t kept;
    std::size_t limit;
    const char* limit_name;
    const char* streaming_call;

    void operator()(std::span<const Pair> chunk) const {
        if (chunk.size() > limit - (pairs.size() - kept)) {
            throw PairLimitError("detect: more than " + std::to_string(limit) + " overlapping pairs (" + limit_name +
                                 "); use " + streaming_call + " to consume them in chunks");
        }
        pairs.insert(pairs.end(), chunk.begin(), chunk.end());
    }
};

/// Runs `fill` (a callable that appends to `items` and returns a result), then leaves in
/// `items` exactly what it appended. The old contents stay in front until it succeeded, so that
/// a throw (an invalid box, the pair limit, an allocation) leaves them as they were; capacity
/// the failed call added is given back, since past a pair limit it may be gigabytes. An empty
/// vector costs nothing more than a plain collection.
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
