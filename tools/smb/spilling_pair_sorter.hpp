// SPDX-License-Identifier: MIT
#pragma once
// Sorts the pairs of one frame in bounded memory: an external merge sort. Pairs are gathered in
// memory up to a limit; past it each full run is sorted and spilled to an anonymous temporary
// file, and the runs are merged at the end. A frame of 100 000 identical boxes has 5·10^9 pairs
// (80 GB as binary pairs): its pairs then cost disk, not memory.

#include <cstddef>
#include <cstdio>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "smb/pair.hpp"

namespace smb::io {

class SpillingPairSorter {
public:
    /// Receives the sorted pairs, in order, in chunks.
    using SortedSink = std::function<void(std::span<const Pair>)>;

    /// `pairs_in_memory`: the most pairs held in memory at once (at least 2); the merge reads
    /// every run through its own share of that.
    explicit SpillingPairSorter(std::size_t pairs_in_memory);
    ~SpillingPairSorter();
    SpillingPairSorter(const SpillingPairSorter&) = delete;
    SpillingPairSorter& operator=(const SpillingPairSorter&) = delete;

    void add(std::span<const Pair> pairs);

    /// Hands every pair added since the last finish() to `sink` in (a, b) order, then forgets
    /// them. Throws std::runtime_error if a temporary file cannot be written or read.
    void finish(const SortedSink& sink);

    /// Number of runs spilled to disk since construction, for messages and tests.
    [[nodiscard]] std::size_t runs_spilled() const noexcept { return runs_spilled_; }

private:
    struct FileCloser {
        void operator()(std::FILE* file) const noexcept { std::fclose(file); }
    };
    using TemporaryFile = std::unique_ptr<std::FILE, FileCloser>;

    void spill();
    void merge_runs(const SortedSink& sink);

    std::size_t pairs_in_memory_;
    std::vector<Pair> buffer_;
    std::vector<TemporaryFile> runs_;
    std::size_t runs_spilled_ = 0;
};

}  // namespace smb::io
