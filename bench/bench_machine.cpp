// SPDX-License-Identifier: MIT
// What the machine's memory gives a second thread, apart from smb: the ceiling on the speedup of
// the passes that are bound by memory (the gather of the caller's boxes in cell order, the cell
// lists' reads and writes). Two access patterns smb's step is made of, on one thread and on two:
//
// - gather: 24-byte records (a float box) read in a random order from 96 MiB, far beyond the
//   last-level cache, as the gather reads the caller's boxes by slot;
// - stream: a 64 MiB array copied, as the levels write their lists and the pairs are copied out.
//
//   ./build/bench/smb_bench_machine --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// items_per_second is summed over the threads: the two-thread row over the one-thread row is the
// most the second thread can add to a pass of that kind.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace {

struct Record {
    std::array<float, 6> coordinates;
};

constexpr std::size_t kRecords = (std::size_t{96} << 20) / sizeof(Record);
constexpr std::size_t kStreamBytes = std::size_t{64} << 20;

const std::vector<Record>& records() {
    static const std::vector<Record> all = [] {
        std::vector<Record> made(kRecords);
        for (std::size_t i = 0; i < made.size(); ++i) made[i].coordinates.fill(static_cast<float>(i % 1000));
        return made;
    }();
    return all;
}

// One random order per thread, so that two threads do not share the lines they miss on.
const std::vector<std::uint32_t>& random_order(int thread) {
    static const std::array<std::vector<std::uint32_t>, 2> orders = [] {
        std::array<std::vector<std::uint32_t>, 2> made;
        for (std::size_t t = 0; t < made.size(); ++t) {
            made[t].resize(kRecords);
            std::iota(made[t].begin(), made[t].end(), 0U);
            std::mt19937_64 random(7 + t);
            std::shuffle(made[t].begin(), made[t].end(), random);
        }
        return made;
    }();
    return orders[static_cast<std::size_t>(thread) % orders.size()];
}

void gather(benchmark::State& state) {
    const std::vector<Record>& from = records();
    const std::vector<std::uint32_t>& order = random_order(state.thread_index());
    constexpr std::size_t kBatch = std::size_t{1} << 20;
    std::vector<Record> to(kBatch);
    std::size_t start = 0;
    for (auto _ : state) {
        // Prefetched ahead, as smb's gather is, so that the misses overlap.
        constexpr std::size_t ahead = 64;
        for (std::size_t i = 0; i < kBatch; ++i) {
            const std::size_t at = (start + i) % kRecords;
            __builtin_prefetch(&from[order[(at + ahead) % kRecords]]);
            to[i] = from[order[at]];
        }
        start = (start + kBatch) % kRecords;
        benchmark::DoNotOptimize(to.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * kBatch * sizeof(Record)));
}

void stream(benchmark::State& state) {
    std::vector<char> from(kStreamBytes, 1);
    std::vector<char> to(kStreamBytes, 2);
    for (auto _ : state) {
        std::memcpy(to.data(), from.data(), kStreamBytes);
        benchmark::DoNotOptimize(to.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * kStreamBytes));
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kStreamBytes));
}

}  // namespace

BENCHMARK(gather)->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(stream)->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond);
