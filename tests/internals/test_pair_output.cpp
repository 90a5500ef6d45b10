// SPDX-License-Identifier: MIT
// PairOutput: pairs one at a time and in runs, to a caller's sink in chunks or straight into a
// vector (the PairAppender of detect(pairs)), before and after a flush, with the pair limit.

#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/pair_output.hpp"

namespace smb::detail {
namespace {

// Writes pairs (i, i + 1) for i in [from, to): one at a time for even i, else in a run.
void write_pairs(PairOutput& output, BoxId from, BoxId to) {
    for (BoxId i = from; i < to; ++i) {
        if (i % 2 == 0) {
            output(i + 1, i);
        } else {
            const Pair run[] = {Pair{i, i + 1}};
            output.append(run);
        }
    }
}

std::vector<Pair> pairs_from(BoxId from, BoxId to) {
    std::vector<Pair> pairs;
    for (BoxId i = from; i < to; ++i) pairs.push_back(Pair{i, i + 1});
    return pairs;
}

TEST(PairOutput, ChunksReachTheSinkInOrderAndAfterAFlush) {
    std::vector<Pair> chunk;
    std::vector<Pair> received;
    std::size_t largest = 0;
    const PairSink sink = [&](std::span<const Pair> pairs) {
        largest = std::max(largest, pairs.size());
        received.insert(received.end(), pairs.begin(), pairs.end());
    };
    std::size_t count = 0;
    PairOutput output(chunk, 7, sink, count);
    write_pairs(output, 0, 100);
    output.flush();
    write_pairs(output, 100, 150);
    const std::vector<Pair> run = pairs_from(150, 170);
    output.append(run);
    output.flush();
    EXPECT_EQ(received, pairs_from(0, 170));
    EXPECT_EQ(count, 170U);
    EXPECT_LE(largest, 7U);
}

TEST(PairOutput, AVectorIsWrittenDirectlyAfterItsPairsAndTrimmedAtEachFlush) {
    std::vector<Pair> pairs = {Pair{1000, 1001}};
    const PairAppender appender{pairs, 1, 100000, "limit", "detect(sink)"};
    const PairSink sink(std::cref(appender));
    std::vector<Pair> unused_chunk;
    std::size_t count = 0;
    PairOutput output(unused_chunk, 7, sink, count);
    write_pairs(output, 0, 9000);  // rooms of 4096 and a part
    output.flush();
    EXPECT_EQ(pairs.size(), 9001U);
    write_pairs(output, 9000, 9010);  // after a flush: room again
    const std::vector<Pair> run = pairs_from(9010, 20000);
    output.append(run);
    output.flush();
    std::vector<Pair> expected = {Pair{1000, 1001}};
    const std::vector<Pair> written = pairs_from(0, 20000);
    expected.insert(expected.end(), written.begin(), written.end());
    EXPECT_EQ(pairs, expected);
    EXPECT_EQ(count, 20000U);
    EXPECT_TRUE(unused_chunk.empty()) << "no chunk is held when the pairs go to the vector";
}

TEST(PairOutput, AVectorPastItsLimitThrowsAtTheExactCount) {
    for (const std::size_t limit : {0U, 1U, 4095U, 4096U, 4097U, 9999U, 10000U}) {
        std::vector<Pair> pairs = {Pair{1000, 1001}};
        const PairAppender appender{pairs, 1, limit, "limit", "detect(sink)"};
        const PairSink sink(std::cref(appender));
        std::vector<Pair> unused_chunk;
        std::size_t count = 0;
        PairOutput output(unused_chunk, 64, sink, count);
        auto write = [&] {
            write_pairs(output, 0, 10000);
            output.flush();
        };
        if (limit >= 10000) {
            write();
            EXPECT_EQ(pairs.size(), 10001U);
        } else {
            EXPECT_THROW(write(), PairLimitError) << limit;
        }
    }
}

}  // namespace
}  // namespace smb::detail
