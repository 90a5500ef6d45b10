// SPDX-License-Identifier: MIT
#pragma once
// A list of pairs laid out by a hash of the pair into 2^bits partitions of about a thousand
// pairs each: two lists hashed alike are compared partition by partition, each partition's
// table small enough to stay in the cache, without sorting either list. One counting pass and
// one scattering pass, as a radix sort's single digit.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/growth.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// Multiplicative hashing: the top bits of the last product depend on every bit of both ids.
/// The partition takes the top bits, a partition's table the bits below them.
[[nodiscard]] inline std::uint64_t pair_hash(const Pair& pair) noexcept {
    return ((pair.a * 0x9E3779B97F4A7C15ULL) ^ pair.b) * 0xD6E8FEB86659FD93ULL;
}

/// About this many pairs per partition: their table (two slots a pair, 4 bytes a slot) and the
/// pairs themselves fit in a core's L2 with room to spare.
inline constexpr std::size_t kPairsPerPartition = 1024;
inline constexpr int kMaxPartitionBits = 24;

/// The partition bits for `count` pairs: the fewest that leave about kPairsPerPartition each.
[[nodiscard]] inline int partition_bits_for(std::size_t count) noexcept {
    int bits = 0;
    while (bits < kMaxPartitionBits && (count >> bits) > kPairsPerPartition) ++bits;
    return bits;
}

struct PairPartitions {
    std::vector<Pair> pairs;
    /// offsets[p] .. offsets[p + 1]: partition p's pairs; 2^bits + 1 entries.
    std::vector<std::uint32_t> offsets{0, 0};
    int bits = 0;

    [[nodiscard]] std::size_t size() const noexcept { return pairs.size(); }
    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return pairs.capacity() * sizeof(Pair) + offsets.capacity() * sizeof(std::uint32_t);
    }
    void clear() {
        std::vector<Pair>().swap(pairs);
        offsets.assign(2, 0);
        bits = 0;
    }

    /// Lays out `source` by partition. Checks a < b of every pair first and throws
    /// ArgumentError otherwise, with this object unchanged.
    void assign(std::span<const Pair> source) {
        if (source.size() >= UINT32_MAX)
            throw ArgumentError("PairEvents::update: at most " + std::to_string(UINT32_MAX - 1) + " pairs");
        const int new_bits = partition_bits_for(source.size());
        const int shift = 64 - new_bits;
        const std::size_t parts = std::size_t{1} << new_bits;
        std::vector<std::uint32_t> counts(parts + 1, 0);
        for (std::size_t i = 0; i < source.size(); ++i) {
            const Pair& pair = source[i];
            if (pair.a >= pair.b) {
                throw ArgumentError("PairEvents::update: pair " + std::to_string(i) + " is (" + std::to_string(pair.a) +
                                    ", " + std::to_string(pair.b) + "); every pair must have a < b");
            }
            // A shift by 64 is undefined: with one partition every pair goes to partition 0.
            if (new_bits != 0) ++counts[(pair_hash(pair) >> shift) + 1];
        }
        if (new_bits == 0) counts[1] = static_cast<std::uint32_t>(source.size());
        for (std::size_t p = 0; p < parts; ++p) counts[p + 1] += counts[p];
        resize_with_slack(pairs, source.size());
        offsets.swap(counts);
        bits = new_bits;
        if (new_bits == 0) {
            std::copy(source.begin(), source.end(), pairs.begin());
            return;
        }
        // counts now holds the old offsets; reuse it as the write cursors.
        counts.assign(offsets.begin(), offsets.end() - 1);
        for (const Pair& pair : source) pairs[counts[pair_hash(pair) >> shift]++] = pair;
    }
};

}  // namespace smb::detail
