// SPDX-License-Identifier: MIT
#pragma once
// Sorting the events by (a, b). Steps with much motion change a quarter of the pairs (the
// paper's environment at 1M boxes, update factor 1e-3: some 400k events a step), and a
// comparison sort of those cost more than the diff that found them. Where both names fit in
// 32 bits, as indices and dense ids do, a least-significant-digit radix sort on the key
// (a << w) | b, w the width of the largest name, is a few linear passes. The passes move the
// 8-byte keys, not the 16-byte pairs: half the memory traffic of every pass.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "smb/pair.hpp"

namespace smb::detail {

/// The scratch of sort_pairs_fast(), kept between sorts so that none allocates.
struct PairSortScratch {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint64_t> spare;

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (keys.capacity() + spare.capacity()) * sizeof(std::uint64_t);
    }
};

/// Sorts `pairs` by (a, b).
inline void sort_pairs_fast(std::vector<Pair>& pairs, PairSortScratch& scratch) {
    constexpr std::size_t kSmall = 4096;
    if (pairs.size() < kSmall) {
        std::sort(pairs.begin(), pairs.end());
        return;
    }
    BoxId names = 0;
    for (const Pair& pair : pairs) names |= pair.a | pair.b;
    const int width = static_cast<int>(std::bit_width(names));
    if (2 * width > 64) {
        std::sort(pairs.begin(), pairs.end());
        return;
    }
    constexpr int kDigitBits = 11;
    constexpr std::size_t kDigits = std::size_t{1} << kDigitBits;
    const int passes = (2 * width + kDigitBits - 1) / kDigitBits;
    auto& keys = scratch.keys;
    auto& spare = scratch.spare;
    keys.resize(pairs.size());
    spare.resize(pairs.size());
    // The keys, and every pass's counts, in one read of the pairs.
    std::vector<std::array<std::uint32_t, kDigits>> counts(static_cast<std::size_t>(passes));
    for (auto& histogram : counts) histogram.fill(0);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        const std::uint64_t key = (pairs[i].a << width) | pairs[i].b;
        keys[i] = key;
        for (int p = 0; p < passes; ++p)
            ++counts[static_cast<std::size_t>(p)][(key >> (p * kDigitBits)) & (kDigits - 1)];
    }
    for (int p = 0; p < passes; ++p) {
        auto& histogram = counts[static_cast<std::size_t>(p)];
        // A digit every pair shares moves nothing.
        if (std::find(histogram.begin(), histogram.end(), static_cast<std::uint32_t>(pairs.size())) != histogram.end())
            continue;
        std::uint32_t sum = 0;
        for (auto& count : histogram) sum += std::exchange(count, sum);
        const int shift = p * kDigitBits;
        for (const std::uint64_t key : keys) spare[histogram[(key >> shift) & (kDigits - 1)]++] = key;
        keys.swap(spare);
    }
    const std::uint64_t low = (std::uint64_t{1} << width) - 1;
    for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i] = Pair{keys[i] >> width, keys[i] & low};
}

}  // namespace smb::detail
