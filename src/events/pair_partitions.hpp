// SPDX-License-Identifier: MIT
#pragma once
// A list of pairs laid out by a hash of the pair into 2^bits partitions of about a thousand
// pairs each: two lists hashed alike are compared partition by partition, each partition's
// table small enough to stay in the cache, without sorting either list. One counting pass and
// one scattering pass, as a radix sort's single digit.
//
// Where every name fits in 32 bits (indices, dense ids: the common case) a pair is held as one
// 64-bit word (pack_pair() below), which halves the memory both passes and the comparison move and
// is its own hash; other lists hold the pairs as they are. The hash is of the pair, not of its
// form, so lists of either form share one layout.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/growth.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

using PackedPair = std::uint64_t;

inline constexpr std::uint64_t kMix = 0xD6E8FEB86659FD93ULL;
/// The inverse of kMix modulo 2^64 (Newton's iteration doubles the correct bits each round).
[[nodiscard]] constexpr std::uint64_t inverse_of(std::uint64_t odd) noexcept {
    std::uint64_t inverse = odd;
    for (int round = 0; round < 6; ++round) inverse *= 2 - odd * inverse;
    return inverse;
}
inline constexpr std::uint64_t kUnmix = inverse_of(kMix);
static_assert(kMix * kUnmix == 1);

/// The packed form of a pair of 32-bit names: the word a << 32 | b through a bijection (an
/// xor-shift, then a multiplication by an odd constant), so that the word is its own hash: the
/// passes over the lists never hash a packed pair, and two packed pairs are equal when their
/// words are. Multiplicative hashing: the top bits depend on every bit of both names.
[[nodiscard]] inline PackedPair pack_pair(BoxId a, BoxId b) noexcept {
    const std::uint64_t word = a << 32 | b;
    return (word ^ (word >> 32)) * kMix;
}
[[nodiscard]] inline Pair unpacked(const Pair& pair) noexcept { return pair; }
[[nodiscard]] inline Pair unpacked(PackedPair pair) noexcept {
    const std::uint64_t mixed = pair * kUnmix;
    const std::uint64_t word = mixed ^ (mixed >> 32);
    return {word >> 32, word & 0xFFFFFFFFU};
}
[[nodiscard]] inline bool same_pair(PackedPair x, PackedPair y) noexcept { return x == y; }
template <class X, class Y>
[[nodiscard]] bool same_pair(const X& x, const Y& y) noexcept {
    return unpacked(x) == unpacked(y);
}

/// The hash of a pair, the same in either form: the partition takes its top bits, a partition's
/// table the bits below them. A pair of 32-bit names hashes as its packed word (a < b, so b
/// bounds both names).
[[nodiscard]] inline std::uint64_t pair_hash(PackedPair pair) noexcept { return pair; }
[[nodiscard]] inline std::uint64_t pair_hash(const Pair& pair) noexcept {
    if (pair.b <= 0xFFFFFFFFU) return pack_pair(pair.a, pair.b);
    return ((pair.a * 0x9E3779B97F4A7C15ULL) ^ pair.b) * kMix;
}

/// About this many pairs per partition: their table (two slots a pair, 4 bytes a slot) and the
/// pairs themselves fit in a core's L1 and L2 caches.
inline constexpr std::size_t kPairsPerPartition = 1024;
inline constexpr int kMaxPartitionBits = 24;

/// The partition bits for `count` pairs: the fewest that leave about kPairsPerPartition each.
[[nodiscard]] inline int partition_bits_for(std::size_t count) noexcept {
    int bits = 0;
    while (bits < kMaxPartitionBits && (count >> bits) > kPairsPerPartition) ++bits;
    return bits;
}

struct PairPartitions {
    /// The pairs in one of two forms: `packed` when `is_packed`, else `wide`.
    std::vector<PackedPair> packed;
    std::vector<Pair> wide;
    bool is_packed = true;
    /// offsets[p] .. offsets[p + 1]: partition p's pairs; 2^bits + 1 entries.
    std::vector<std::uint32_t> offsets{0, 0};
    int bits = 0;

    [[nodiscard]] std::size_t size() const noexcept { return is_packed ? packed.size() : wide.size(); }
    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return packed.capacity() * sizeof(PackedPair) + wide.capacity() * sizeof(Pair) +
               offsets.capacity() * sizeof(std::uint32_t);
    }

    /// Lays out `source` by partition. Checks a < b of every pair first and throws
    /// ArgumentError otherwise, with this object unchanged.
    void assign(std::span<const Pair> source) {
        if (source.size() >= UINT32_MAX)
            throw ArgumentError("PairEvents::update: at most " + std::to_string(UINT32_MAX - 1) + " pairs");
        const int new_bits = partition_bits_for(source.size());
        // A shift by 64 is undefined: one partition is the hash shifted by 63, then halved.
        const auto partition_of = [new_bits](const Pair& pair) {
            return static_cast<std::size_t>((pair_hash(pair) >> (63 - new_bits)) >> 1);
        };
        const std::size_t parts = std::size_t{1} << new_bits;
        std::vector<std::uint32_t> counts(parts + 1, 0);
        BoxId names = 0;
        for (std::size_t i = 0; i < source.size(); ++i) {
            const Pair& pair = source[i];
            if (pair.a >= pair.b) {
                throw ArgumentError("PairEvents::update: pair " + std::to_string(i) + " is (" + std::to_string(pair.a) +
                                    ", " + std::to_string(pair.b) + "); every pair must have a < b");
            }
            names |= pair.b;
            ++counts[partition_of(pair) + 1];
        }
        for (std::size_t p = 0; p < parts; ++p) counts[p + 1] += counts[p];
        const bool pack = names <= 0xFFFFFFFFU;
        if (pack) {
            resize_with_slack(packed, source.size());
        } else {
            resize_with_slack(wide, source.size());
        }
        std::vector<std::uint32_t> cursors(counts.begin(), counts.end() - 1);
        offsets.swap(counts);
        bits = new_bits;
        is_packed = pack;
        if (pack) {
            wide.clear();
            for (const Pair& pair : source) {
                const PackedPair word = pack_pair(pair.a, pair.b);  // its own hash
                packed[cursors[(word >> (63 - new_bits)) >> 1]++] = word;
            }
        } else {
            packed.clear();
            for (const Pair& pair : source) wide[cursors[partition_of(pair)]++] = pair;
        }
    }
};

}  // namespace smb::detail
