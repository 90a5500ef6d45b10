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
#include <utility>
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

    /// Lays out `source` by partition, on `threads` threads (each counts and scatters its own
    /// contiguous share; the layout depends on the thread count, the events do not). Checks
    /// a < b of every pair first and throws ArgumentError for the first that fails otherwise,
    /// with this object unchanged.
    void assign(std::span<const Pair> source, int threads) {
        if (source.size() >= UINT32_MAX)
            throw ArgumentError("PairEvents::update: at most " + std::to_string(UINT32_MAX - 1) + " pairs");
        const int new_bits = partition_bits_for(source.size());
        // A shift by 64 is undefined: one partition is the hash shifted by 63, then halved.
        const auto partition_of = [new_bits](const Pair& pair) {
            return static_cast<std::size_t>((pair_hash(pair) >> (63 - new_bits)) >> 1);
        };
        const std::size_t parts = std::size_t{1} << new_bits;
        const std::size_t n = source.size();
        constexpr std::size_t kPairsPerThread = std::size_t{1} << 16;
        const int team = std::max(1, std::min(threads, static_cast<int>(n / kPairsPerThread)));
        const auto share = [&](int t) {
            return std::pair{n * static_cast<std::size_t>(t) / static_cast<std::size_t>(team),
                             n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(team)};
        };
        // Counts of thread t at [t * parts, (t + 1) * parts), then its cursors.
        std::vector<std::uint32_t> counts(static_cast<std::size_t>(team) * parts, 0);
        std::vector<BoxId> names(static_cast<std::size_t>(team), 0);
        std::vector<std::size_t> first_bad(static_cast<std::size_t>(team), SIZE_MAX);
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
        for (int t = 0; t < team; ++t) {
            const auto [lo, hi] = share(t);
            std::uint32_t* count = counts.data() + static_cast<std::size_t>(t) * parts;
            BoxId seen = 0;
            for (std::size_t i = lo; i < hi; ++i) {
                const Pair& pair = source[i];
                if (pair.a >= pair.b) {
                    first_bad[static_cast<std::size_t>(t)] = i;
                    break;
                }
                seen |= pair.b;
                ++count[partition_of(pair)];
            }
            names[static_cast<std::size_t>(t)] = seen;
        }
        for (const std::size_t i : first_bad) {
            if (i != SIZE_MAX) {
                throw ArgumentError("PairEvents::update: pair " + std::to_string(i) + " is (" +
                                    std::to_string(source[i].a) + ", " + std::to_string(source[i].b) +
                                    "); every pair must have a < b");
            }
        }
        BoxId all_names = 0;
        for (const BoxId seen : names) all_names |= seen;
        // Partition after partition, each thread's pairs after the previous thread's.
        std::vector<std::uint32_t> starts(parts + 1, 0);
        std::uint32_t running = 0;
        for (std::size_t p = 0; p < parts; ++p) {
            starts[p] = running;
            for (std::size_t t = 0; t < static_cast<std::size_t>(team); ++t)
                running += std::exchange(counts[t * parts + p], running);
        }
        starts[parts] = running;
        const bool pack = all_names <= 0xFFFFFFFFU;
        if (pack) {
            resize_with_slack(packed, n);
        } else {
            resize_with_slack(wide, n);
        }
        offsets.swap(starts);
        bits = new_bits;
        is_packed = pack;
        if (pack) {
            wide.clear();
        } else {
            packed.clear();
        }
#pragma omp parallel for num_threads(team) schedule(static, 1) if (team > 1)
        for (int t = 0; t < team; ++t) {
            const auto [lo, hi] = share(t);
            std::uint32_t* cursor = counts.data() + static_cast<std::size_t>(t) * parts;
            if (pack) {
                for (std::size_t i = lo; i < hi; ++i) {
                    const PackedPair word = pack_pair(source[i].a, source[i].b);  // its own hash
                    packed[cursor[(word >> (63 - new_bits)) >> 1]++] = word;
                }
            } else {
                for (std::size_t i = lo; i < hi; ++i) wide[cursor[partition_of(source[i])]++] = source[i];
            }
        }
    }
};

}  // namespace smb::detail
