// SPDX-License-Identifier: MIT
#pragma once
// The detection's pairs as sorted keys (a << w) | b, w the width of the largest proxy id: the
// order of the candidates, compared in one integer comparison. With ten thousand to a million
// proxies a key has 28 to 40 bits, and a least-significant-digit radix sort with digits of up to
// 16 bits sorts the keys in two or three passes.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace smb::bullet::detail {

/// Sorts `keys`, of `key_bits` bits each; `spare` and `counts` are its room, kept between sorts
/// by the caller so that none allocates.
inline void sort_pair_keys(std::vector<std::uint64_t>& keys, int key_bits, std::vector<std::uint64_t>& spare,
                           std::vector<std::uint32_t>& counts) {
    constexpr std::size_t small = 2048;
    if (keys.size() < small || key_bits <= 0) {
        std::sort(keys.begin(), keys.end());
        return;
    }
    constexpr int widest_digit = 16;
    const int passes = (key_bits + widest_digit - 1) / widest_digit;
    const int digit_bits = (key_bits + passes - 1) / passes;
    const std::size_t digits = std::size_t{1} << digit_bits;
    const std::uint64_t digit_mask = digits - 1;
    // Every pass's counts in one read of the keys.
    counts.assign(digits * static_cast<std::size_t>(passes), 0);
    for (const std::uint64_t key : keys) {
        for (int p = 0; p < passes; ++p) {
            ++counts[static_cast<std::size_t>(p) * digits + ((key >> (p * digit_bits)) & digit_mask)];
        }
    }
    spare.resize(keys.size());
    for (int p = 0; p < passes; ++p) {
        std::uint32_t* count = counts.data() + static_cast<std::size_t>(p) * digits;
        // A digit every key shares moves nothing.
        if (std::find(count, count + digits, static_cast<std::uint32_t>(keys.size())) != count + digits) continue;
        std::uint32_t sum = 0;
        for (std::size_t d = 0; d < digits; ++d) sum += std::exchange(count[d], sum);
        const int shift = p * digit_bits;
        for (const std::uint64_t key : keys) spare[count[(key >> shift) & digit_mask]++] = key;
        keys.swap(spare);
    }
}

}  // namespace smb::bullet::detail
