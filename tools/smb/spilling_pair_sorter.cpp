// SPDX-License-Identifier: MIT
#include "spilling_pair_sorter.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace smb::io {

namespace {

constexpr std::size_t kOutputChunk = std::size_t{1} << 16;

/// `what`, with the system's reason where errno holds one (a full disk says so).
std::string with_reason(const std::string& what) { return errno == 0 ? what : what + ": " + std::strerror(errno); }

}  // namespace

SpillingPairSorter::SpillingPairSorter(std::size_t pairs_in_memory)
    : pairs_in_memory_(std::max<std::size_t>(pairs_in_memory, 2)) {}

SpillingPairSorter::~SpillingPairSorter() = default;

void SpillingPairSorter::add(std::span<const Pair> pairs) {
    while (!pairs.empty()) {
        // Spill only when more pairs arrive at a full buffer: a frame of exactly the allowance
        // stays in memory.
        if (buffer_.size() == pairs_in_memory_) spill();
        const std::size_t taken = std::min(pairs_in_memory_ - buffer_.size(), pairs.size());
        buffer_.insert(buffer_.end(), pairs.begin(), pairs.begin() + static_cast<std::ptrdiff_t>(taken));
        pairs = pairs.subspan(taken);
    }
}

void SpillingPairSorter::spill() {
    std::sort(buffer_.begin(), buffer_.end());
    errno = 0;
    TemporaryFile file(std::tmpfile());
    if (!file) throw std::runtime_error(with_reason("cannot create a temporary file to sort the pairs of a frame"));
    if (std::fwrite(buffer_.data(), sizeof(Pair), buffer_.size(), file.get()) != buffer_.size() ||
        std::fflush(file.get()) != 0)
        throw std::runtime_error(with_reason("cannot write the pairs of a frame to a temporary file"));
    std::rewind(file.get());
    runs_.push_back(std::move(file));
    ++runs_spilled_;
    buffer_.clear();
}

void SpillingPairSorter::finish(const SortedSink& sink) {
    if (runs_.empty()) {
        std::sort(buffer_.begin(), buffer_.end());
        for (std::size_t first = 0; first < buffer_.size(); first += kOutputChunk) {
            const std::size_t count = std::min(kOutputChunk, buffer_.size() - first);
            sink(std::span<const Pair>(buffer_).subspan(first, count));
        }
        buffer_.clear();
        return;
    }
    if (!buffer_.empty()) spill();
    buffer_.clear();
    buffer_.shrink_to_fit();
    merge_runs(sink);
    runs_.clear();
}

void SpillingPairSorter::merge_runs(const SortedSink& sink) {
    // Each run is read through a window of an equal share of the memory allowance.
    const std::size_t window = std::max<std::size_t>(pairs_in_memory_ / (runs_.size() + 1), 1);
    struct Run {
        std::vector<Pair> pairs;
        std::size_t next = 0;
    };
    std::vector<Run> runs(runs_.size());
    auto refill = [&](std::size_t r) {
        runs[r].pairs.resize(window);
        const std::size_t got = std::fread(runs[r].pairs.data(), sizeof(Pair), window, runs_[r].get());
        if (got < window && std::ferror(runs_[r].get()))
            throw std::runtime_error("cannot read back the pairs of a frame from a temporary file");
        runs[r].pairs.resize(got);
        runs[r].next = 0;
        return got > 0;
    };
    using Head = std::pair<Pair, std::size_t>;  // the smallest unread pair of a run, and the run
    std::priority_queue<Head, std::vector<Head>, std::greater<>> heads;
    for (std::size_t r = 0; r < runs.size(); ++r)
        if (refill(r)) heads.emplace(runs[r].pairs[0], r);

    std::vector<Pair> output;
    output.reserve(std::min(window, kOutputChunk));
    while (!heads.empty()) {
        const auto [pair, r] = heads.top();
        heads.pop();
        output.push_back(pair);
        if (output.size() == output.capacity()) {
            sink(output);
            output.clear();
        }
        Run& run = runs[r];
        if (++run.next < run.pairs.size() || refill(r)) heads.emplace(run.pairs[run.next], r);
    }
    if (!output.empty()) sink(output);
}

}  // namespace smb::io
