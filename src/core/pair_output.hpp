// SPDX-License-Identifier: MIT
#pragma once
// The pairs of one detection on their way to the caller's sink, in chunks.

#include <algorithm>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
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

/// The sink of detect(..., std::vector<Pair>&): appends every chunk to `pairs` after the `kept`
/// pairs it held before, and throws PairLimitError past `limit` new pairs, naming `limit_name`
/// (the settings field) and `streaming_call` (the way to take any number of pairs). Handed over as
/// std::cref(appender), so that the PairSink holds a reference and allocates nothing; PairOutput
/// recognises it there and writes the pairs straight into `pairs`.
struct PairAppender {
    std::vector<Pair>& pairs;
    std::size_t kept;
    std::size_t limit;
    const char* limit_name;
    const char* streaming_call;

    /// Throws PairLimitError if `adding` more pairs would pass the limit.
    void check_room(std::size_t adding) const {
        const std::size_t added = pairs.size() - kept;
        if (added > limit || adding > limit - added) {
            throw PairLimitError("detect: more than " + std::to_string(limit) + " overlapping pairs (" + limit_name +
                                 "); use " + streaming_call + " to consume them in chunks");
        }
    }

    void operator()(std::span<const Pair> chunk) const {
        check_room(chunk.size());
        pairs.insert(pairs.end(), chunk.begin(), chunk.end());
    }
};

/// The PairAppender that `sink` holds (as std::cref(appender)), or null. Out of line: inlined
/// into the detection's units, std::function::target() makes GCC 12 warn of a pointer used
/// uninitialized inside it (-Wmaybe-uninitialized), a false alarm.
[[nodiscard]] const PairAppender* appender_behind(const PairSink& sink) noexcept;

/// Hands pairs to the caller's sink in chunks of the settings' size: one pair at a time (the
/// paper's pipeline) or runs already in (a < b) order (the persistent pipeline; a run that fills
/// whole chunks goes to the sink without another copy). Where the sink is a PairAppender, the
/// pairs are written into the caller's vector itself, kDirectRoom at a time: once, not into a
/// chunk and then copied.
class PairOutput {
public:
    /// `chunk` is the caller's buffer, kept between detections so that none allocates it again.
    /// It is held at the chunk's full size, and the pairs are written by a cursor into it: a pair
    /// is then one store, where push_back tests the capacity and calls out of line.
    PairOutput(std::vector<Pair>& chunk, std::size_t chunk_size, const PairSink& sink, std::size_t& count)
        : chunk_(chunk), chunk_size_(chunk_size), sink_(sink), count_(count) {
        if (const PairAppender* appender = appender_behind(sink)) {
            direct_ = appender;
            counted_ = direct_->pairs.size();
            close_at_end();
            return;
        }
        chunk_.resize(chunk_size_);
        next_ = chunk_.data();
        end_ = next_ + chunk_size_;
    }

    // Inlined into the cell check's report loop (GCC would leave it a call there); a full room
    // stays out of line. Room is made before a pair, not after: a flushed output takes more.
    [[gnu::always_inline]] inline void operator()(BoxId a, BoxId b) {
        if (next_ == end_) full();
        *next_++ = ordered_pair(a, b);
    }

    void append(std::span<const Pair> ordered) {
        if (direct_ != nullptr) {
            // Inserted after the pairs written, not copied over zeroed room: one write of each.
            close_direct();
            direct_->check_room(ordered.size());
            direct_->pairs.insert(direct_->pairs.end(), ordered.begin(), ordered.end());
            // No room made: a run after a run (the threads' blocks) would zero one for nothing.
            close_at_end();
            return;
        }
        while (!ordered.empty()) {
            const auto filled = static_cast<std::size_t>(next_ - chunk_.data());
            if (filled == 0 && ordered.size() >= chunk_size_) {
                count_ += chunk_size_;
                sink_(ordered.first(chunk_size_));
                ordered = ordered.subspan(chunk_size_);
                continue;
            }
            const std::size_t take = std::min(ordered.size(), chunk_size_ - filled);
            next_ = std::copy_n(ordered.begin(), take, next_);
            ordered = ordered.subspan(take);
            if (next_ == end_) send_chunk();
        }
    }

    /// Hands on the pairs still held; a vector written directly is trimmed to its pairs (a
    /// later pair makes room again).
    void flush() {
        if (direct_ != nullptr) {
            close_direct();
            close_at_end();
            return;
        }
        if (next_ != chunk_.data()) send_chunk();
    }

private:
    /// Pairs of room the caller's vector grows by at a time: zeroed by resize() and written over
    /// while still in the cache.
    static constexpr std::size_t kDirectRoom = 4096;

    [[gnu::noinline]] void full() {
        if (direct_ == nullptr) {
            send_chunk();
            return;
        }
        close_direct();
        make_room();
    }

    void send_chunk() {
        const auto filled = static_cast<std::size_t>(next_ - chunk_.data());
        count_ += filled;
        next_ = chunk_.data();  // first: a sink that throws leaves an empty chunk behind
        sink_(std::span<const Pair>(chunk_.data(), filled));
    }

    /// The caller's vector trimmed to the pairs written, the limit checked and the count kept.
    void close_direct() {
        std::vector<Pair>& pairs = direct_->pairs;
        const auto used = static_cast<std::size_t>(next_ - pairs.data());
        pairs.resize(used);
        count_ += used - counted_;
        counted_ = used;
        direct_->check_room(0);
    }

    /// No room left after the pairs of the vector: the next pair makes some (full()).
    void close_at_end() noexcept {
        std::vector<Pair>& pairs = direct_->pairs;
        next_ = pairs.data() + pairs.size();
        end_ = next_;
    }

    /// Room for kDirectRoom more pairs after the pairs of the vector (closed: close_direct()).
    void make_room() {
        std::vector<Pair>& pairs = direct_->pairs;
        const std::size_t used = pairs.size();
        pairs.resize(used + kDirectRoom);
        next_ = pairs.data() + used;
        end_ = pairs.data() + pairs.size();
    }

    std::vector<Pair>& chunk_;
    std::size_t chunk_size_;
    const PairSink& sink_;
    std::size_t& count_;
    Pair* next_ = nullptr;  // where the next pair goes
    Pair* end_ = nullptr;   // the end of the room it may go to
    const PairAppender* direct_ = nullptr;
    std::size_t counted_ = 0;  // with direct_: the pairs of the vector already counted
};

}  // namespace smb::detail
