// SPDX-License-Identifier: MIT
#pragma once
// Pairs sorted by (a, b) as integer keys (a << w) | b, w the width of the largest name: one
// comparison a pair, and a least-significant-digit radix sort instead of a comparison sort.
// Steps with much motion change a quarter of the pairs (the paper's environment at 1M boxes,
// update factor 1e-3: some 400k events a step), and a comparison sort of those cost more than
// the diff that found them; the Bullet back end merges a million candidates a step by key.
// With ten thousand to a million names a key has 28 to 40 bits: three or four passes over 8-byte
// keys, half the memory traffic of moving 16-byte pairs.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/tuning.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// The digits of a least-significant-digit radix sort of keys of `key_bits` bits: as few passes
/// as digits of up to tuning::radix_digit_bits allow, the bits shared evenly among them.
struct RadixDigits {
    int passes = 1;
    int bits = 1;
    std::size_t count = 2;

    explicit RadixDigits(int key_bits) noexcept
        : passes((key_bits + tuning::radix_digit_bits - 1) / tuning::radix_digit_bits),
          bits((key_bits + passes - 1) / passes),
          count(std::size_t{1} << bits) {}

    /// Adds `key` to every pass's counts (`counts`: `passes` arrays of `count`).
    void tally(std::uint64_t key, std::uint32_t* counts) const noexcept {
        for (int p = 0; p < passes; ++p)
            ++counts[static_cast<std::size_t>(p) * count + ((key >> (p * bits)) & (count - 1))];
    }
};

/// The passes of the radix sort over `keys`, every pass's counts already tallied.
inline void radix_passes(const RadixDigits& digits, std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& spare,
                         std::vector<std::uint32_t>& counts) {
    spare.resize(keys.size());
    const std::uint64_t digit_mask = digits.count - 1;
    for (int p = 0; p < digits.passes; ++p) {
        std::uint32_t* count = counts.data() + static_cast<std::size_t>(p) * digits.count;
        // A digit every key shares moves nothing.
        if (std::find(count, count + digits.count, static_cast<std::uint32_t>(keys.size())) != count + digits.count)
            continue;
        std::uint32_t sum = 0;
        for (std::size_t d = 0; d < digits.count; ++d) sum += std::exchange(count[d], sum);
        const int shift = p * digits.bits;
        for (const std::uint64_t key : keys) spare[count[(key >> shift) & digit_mask]++] = key;
        keys.swap(spare);
    }
}

/// Sorts `keys`, of `key_bits` bits each; `spare` and `counts` are its room, kept between sorts
/// by the caller so that none allocates.
inline void sort_pair_keys(std::vector<std::uint64_t>& keys, int key_bits, std::vector<std::uint64_t>& spare,
                           std::vector<std::uint32_t>& counts) {
    if (keys.size() < tuning::radix_sort_from || key_bits <= 0) {
        std::sort(keys.begin(), keys.end());
        return;
    }
    const RadixDigits digits(key_bits);
    counts.assign(digits.count * static_cast<std::size_t>(digits.passes), 0);
    for (const std::uint64_t key : keys) digits.tally(key, counts.data());
    radix_passes(digits, keys, spare, counts);
}

/// The room of sort_pairs_fast(), kept between sorts so that none allocates.
struct PairSortScratch {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint64_t> spare;
    std::vector<std::uint32_t> counts;

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (keys.capacity() + spare.capacity()) * sizeof(std::uint64_t) + counts.capacity() * sizeof(std::uint32_t);
    }
};

/// Sorts `pairs` by (a, b): as keys where both names fit in 32 bits (indices and dense ids do),
/// by comparison otherwise.
inline void sort_pairs_fast(std::vector<Pair>& pairs, PairSortScratch& scratch) {
    if (pairs.size() < tuning::radix_sort_from) {
        std::sort(pairs.begin(), pairs.end());
        return;
    }
    BoxId names = 0;
    for (const Pair& pair : pairs) names |= pair.a | pair.b;
    const int width = static_cast<int>(std::bit_width(names));
    if (width == 0 || 2 * width > 64) {
        std::sort(pairs.begin(), pairs.end());
        return;
    }
    // The keys, and every pass's counts, in one read of the pairs.
    const RadixDigits digits(2 * width);
    auto& keys = scratch.keys;
    keys.resize(pairs.size());
    scratch.counts.assign(digits.count * static_cast<std::size_t>(digits.passes), 0);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        keys[i] = (pairs[i].a << width) | pairs[i].b;
        digits.tally(keys[i], scratch.counts.data());
    }
    radix_passes(digits, keys, scratch.spare, scratch.counts);
    const std::uint64_t low = (std::uint64_t{1} << width) - 1;
    for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i] = Pair{keys[i] >> width, keys[i] & low};
}

}  // namespace smb::detail
