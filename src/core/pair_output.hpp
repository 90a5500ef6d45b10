// SPDX-License-Identifier: MIT
#pragma once
// The pairs of one detection on their way to the caller's sink, in chunks.

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// The pair of a and b, the smaller id first. Without a branch: which id is the smaller is a
/// coin toss from pair to pair.
[[nodiscard]] inline Pair ordered_pair(BoxId a, BoxId b) noexcept {
    const BoxId swap = (a ^ b) & (BoxId{0} - BoxId{b < a});
    return Pair{a ^ swap, b ^ swap};
}

/// Hands pairs to the caller's sink in chunks of the settings' size: one pair at a time (the
/// paper's pipeline) or a run of pairs already in (a < b) order (the persistent pipeline, whose
/// runs go to the sink without another copy where they fill whole chunks).
class PairOutput {
public:
    /// `chunk` is the caller's buffer, kept between detections so that none allocates it again.
    /// It is held at the chunk's full size, and filled_ counts the pairs in it: a pair is then
    /// one store, where push_back tests the capacity and calls out of line.
    PairOutput(std::vector<Pair>& chunk, std::size_t chunk_size, const PairSink& sink, std::size_t& count)
        : chunk_(chunk), chunk_size_(chunk_size), sink_(sink), count_(count) {
        chunk_.resize(chunk_size_);
    }

    // Inlined into the cell check's report loop (GCC would leave it a call there); sending a
    // full chunk stays out of line.
    [[gnu::always_inline]] inline void operator()(BoxId a, BoxId b) {
        chunk_[filled_++] = ordered_pair(a, b);
        if (filled_ == chunk_size_) send_chunk();
    }

    void append(std::span<const Pair> ordered) {
        while (!ordered.empty()) {
            if (filled_ == 0 && ordered.size() >= chunk_size_) {
                count_ += chunk_size_;
                sink_(ordered.first(chunk_size_));
                ordered = ordered.subspan(chunk_size_);
                continue;
            }
            const std::size_t take = std::min(ordered.size(), chunk_size_ - filled_);
            std::copy_n(ordered.begin(), take, chunk_.begin() + static_cast<std::ptrdiff_t>(filled_));
            filled_ += take;
            ordered = ordered.subspan(take);
            if (filled_ == chunk_size_) send_chunk();
        }
    }

    void flush() {
        if (filled_ != 0) send_chunk();
    }

private:
    [[gnu::noinline]] void send_chunk() {
        count_ += filled_;
        const std::size_t filled = filled_;
        filled_ = 0;  // first: a sink that throws leaves an empty chunk behind
        sink_(std::span<const Pair>(chunk_.data(), filled));
    }

    std::vector<Pair>& chunk_;
    std::size_t chunk_size_;
    std::size_t filled_ = 0;
    const PairSink& sink_;
    std::size_t& count_;
};

}  // namespace smb::detail
