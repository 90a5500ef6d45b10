// SPDX-License-Identifier: MIT
// The axial cut's quantiles (src/cuts/quantile_select.hpp): recursive selection against the radix
// sort, on fresh keys at every iteration. Repeating one input would let the branch predictor
// learn the selection's comparisons and flatter it several times over, which is not what a cut
// sees: each group's keys are new to it.
//
//   ./build/bench/smb_bench_quantiles --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// Arguments: n keys, cut into max(2, n / 24) segments (the target cell population). Each
// iteration copies one key set of a pool of 256 into the selector, which both ways pay.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "cuts/quantile_select.hpp"

namespace {

template <class Real>
std::vector<std::vector<Real>> key_pool(std::size_t n) {
    std::mt19937_64 random(42);
    std::uniform_real_distribution<Real> coordinate(-50, 50);
    std::vector<std::vector<Real>> pool(256, std::vector<Real>(n));
    for (auto& keys : pool)
        for (Real& key : keys) key = coordinate(random);
    return pool;
}

template <class Real, bool kRadix>
void quantiles(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const auto segments = static_cast<std::uint32_t>(std::max<std::size_t>(2, n / 24));
    const auto pool = key_pool<Real>(n);
    smb::detail::QuantileSelector<Real> selector;
    std::vector<Real> out(segments - 1);
    std::size_t next = 0;
    for (auto _ : state) {
        selector.keys = pool[next++ % pool.size()];
        if constexpr (kRadix) {
            selector.select_by_radix_sort(segments, out.data());
        } else {
            selector.select_by_selection(segments, out.data());
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
}

void sizes(benchmark::internal::Benchmark* bench) {
    for (const std::int64_t n : {64, 128, 256, 1000, 1500, 5000}) bench->Arg(n);
}

BENCHMARK(quantiles<float, false>)->Name("quantiles_selection/float")->Apply(sizes);
BENCHMARK(quantiles<float, true>)->Name("quantiles_radix_sort/float")->Apply(sizes);
BENCHMARK(quantiles<double, false>)->Name("quantiles_selection/double")->Apply(sizes);
BENCHMARK(quantiles<double, true>)->Name("quantiles_radix_sort/double")->Apply(sizes);

}  // namespace
