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

/// Runs `detect` (a callable taking a PairSink) and leaves in `pairs` exactly the pairs it
/// reported. The pairs go after the old contents and are moved to the front once the detection
/// succeeded, so that a throw (an invalid box, the pair limit, an allocation) leaves the old
/// contents as they were; capacity the failed detection added is given back, since past the
/// limit it may be gigabytes. An empty vector costs nothing more than a plain collection.
template <class Detect>
DetectStats collect_pairs(std::vector<Pair>& pairs, std::size_t limit, const char* limit_name,
                          const char* streaming_call, Detect&& detect) {
    const std::size_t kept = pairs.size();
    const std::size_t capacity = pairs.capacity();
    const PairAppender appender{pairs, kept, limit, limit_name, streaming_call};
    try {
        const DetectStats stats = detect(PairSink(std::cref(appender)));
        pairs.erase(pairs.begin(), pairs.begin() + static_cast<std::ptrdiff_t>(kept));
        return stats;
    } catch (...) {
        pairs.resize(kept);
        if (pairs.capacity() > capacity) pairs.shrink_to_fit();
        throw;
    }
}

}  // namespace smb::detail
