// SPDX-License-Identifier: MIT
#pragma once
// A list of pairs laid out by a hash of the pair into 2^bits partitions of about a thousand
// pairs each: two lists hashed alike are compared partition by partition, each partition's
// table small enough to stay in the cache, without sorting either list. On one thread, one
// pass: each partition has room for a little more than its share and a spill takes the rest.
// On several, a counting pass and a scattering pass, as a radix sort's single digit. Measured at
// 1M boxes (3D, update factor 1e-3, 1.6M pairs, 2-core Xeon VM), the layout took 9-10 ms in one
// pass and 14-15 ms counted (5-6 ms of it counting).
//
// Where every name fits in 32 bits (indices, dense ids: the common case) a pair is held as one
// 64-bit word (pack_pair() below), which halves the memory both passes and the comparison move and
// is its own hash; other lists hold the pairs as they are. The hash is of the pair, not of its
// form, so lists of either form share one layout.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/growth.hpp"
#include "core/tuning.hpp"
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

/// The partition of `hash` among 2^bits: its top bits. A shift by 64 is undefined: the hash is
/// shifted by 63, then halved.
[[nodiscard]] inline std::size_t partition_of(std::uint64_t hash, int bits) noexcept {
    return static_cast<std::size_t>((hash >> (63 - bits)) >> 1);
}

/// About this many pairs per partition: their table (32 slots a pair, 4 bytes a slot) and the
/// pairs themselves fit in a core's L2 cache.
inline constexpr std::size_t kPairsPerPartition = tuning::pairs_per_partition;
inline constexpr int kMaxPartitionBits = 24;
inline constexpr std::size_t kPairsPerThread = tuning::event_pairs_per_thread;

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
    /// begins[p] .. ends[p]: partition p's pairs in `packed` or `wide`; 2^bits entries each.
    /// Back to back (ends[p] == begins[p + 1]) unless `gapped`: then each partition has room
    /// for a few more pairs than the mean, and those that found it full are in `spill`
    /// (packed, sorted, hence by partition).
    std::vector<std::uint32_t> begins{0};
    std::vector<std::uint32_t> ends{0};
    std::vector<PackedPair> spill;
    bool gapped = false;
    std::size_t pair_count = 0;
    int bits = 0;

    [[nodiscard]] std::size_t size() const noexcept { return pair_count; }
    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (packed.capacity() + spill.capacity()) * sizeof(PackedPair) + wide.capacity() * sizeof(Pair) +
               (begins.capacity() + ends.capacity()) * sizeof(std::uint32_t);
    }

    /// Calls `f` on every pair, in either form.
    template <class F>
    void for_each(const F& f) const {
        for (std::size_t p = 0; p < begins.size(); ++p) {
            for (std::uint32_t i = begins[p]; i < ends[p]; ++i) {
                if (is_packed) {
                    f(packed[i]);
                } else {
                    f(wide[i]);
                }
            }
        }
        for (const PackedPair pair : spill) f(pair);
    }

    /// The pairs of partitions [u, u + 1) << (bits - unit_bits), of form T: where they lie back
    /// to back, in place; else gathered into `buffer`.
    template <class T>
    [[nodiscard]] std::span<const T> unit(std::size_t u, int unit_bits, std::vector<PackedPair>& buffer) const {
        const std::size_t per_unit = std::size_t{1} << (bits - unit_bits);
        const std::size_t p0 = u * per_unit;
        const std::size_t p1 = p0 + per_unit;
        const auto in_place = [&](const std::vector<T>& list) {
            return std::span<const T>(list.data() + begins[p0], ends[p1 - 1] - begins[p0]);
        };
        if constexpr (std::is_same_v<T, Pair>) {
            return in_place(wide);  // a wide list is never gapped
        } else {
            if (!gapped) return in_place(packed);
            const auto partition_below = [&](PackedPair word, std::size_t p) { return partition_of(word, bits) < p; };
            const auto s0 = std::lower_bound(spill.begin(), spill.end(), p0, partition_below);
            const auto s1 = std::lower_bound(s0, spill.end(), p1, partition_below);
            if (per_unit == 1 && s0 == s1) return in_place(packed);
            buffer.clear();
            for (std::size_t p = p0; p < p1; ++p)
                buffer.insert(buffer.end(), packed.begin() + begins[p], packed.begin() + ends[p]);
            buffer.insert(buffer.end(), s0, s1);
            return buffer;
        }
    }

    /// Lays out `source` by partition, on `threads` threads (the layout depends on the thread
    /// count, the events do not). Throws ArgumentError for the first pair without a < b, with
    /// this object left empty. `watch(pair, thread)` sees every pair while it is at hand, at
    /// least once (a one-pass layout that meets a wide name starts again), on the thread
    /// numbered `thread` of those laying out.
    template <class Watch>
    void assign(std::span<const Pair> source, int threads, const Watch& watch) {
        if (source.size() >= UINT32_MAX)
            throw ArgumentError("PairEvents::update: at most " + std::to_string(UINT32_MAX - 1) + " pairs");
        const int new_bits = partition_bits_for(source.size());
        if ((threads <= 1 || source.size() < 2 * kPairsPerThread) && assign_gapped(source, new_bits, watch)) return;
        assign_counted(source, threads, new_bits, watch);
    }
    void assign(std::span<const Pair> source, int threads) {
        assign(source, threads, [](const Pair&, int) {});
    }

private:
    void make_empty() noexcept {
        packed.clear();
        wide.clear();
        spill.clear();
        begins.assign(1, 0);
        ends.assign(1, 0);
        is_packed = true;
        gapped = false;
        pair_count = 0;
        bits = 0;
    }

    [[noreturn]] void throw_unordered(std::span<const Pair> source, std::size_t i) {
        make_empty();
        throw ArgumentError("PairEvents::update: pair " + std::to_string(i) + " is (" + std::to_string(source[i].a) +
                            ", " + std::to_string(source[i].b) + "); every pair must have a < b");
    }

    /// One pass, no counting: every partition gets room for the mean and some standard
    /// deviations more (the hash spreads the pairs as a Poisson process would), and a pair that
    /// finds its partition full goes to `spill`. Packed lists only: returns false, having laid
    /// out nothing, on meeting a name of more than 32 bits.
    template <class Watch>
    bool assign_gapped(std::span<const Pair> source, int new_bits, const Watch& watch) {
        const std::size_t parts = std::size_t{1} << new_bits;
        const std::size_t n = source.size();
        const std::size_t mean = (n >> new_bits) + 1;
        const auto room =
            mean + tuning::partition_slack_deviations * static_cast<std::size_t>(std::sqrt(static_cast<double>(mean))) +
            16;
        if (parts * room >= UINT32_MAX) return false;
        bits = new_bits;
        is_packed = true;
        gapped = true;
        pair_count = n;
        wide.clear();
        spill.clear();
        resize_with_slack(packed, parts * room);
        begins.resize(parts);
        ends.resize(parts);
        for (std::size_t p = 0; p < parts; ++p) begins[p] = ends[p] = static_cast<std::uint32_t>(p * room);
        PackedPair* out = packed.data();
        std::uint32_t* end = ends.data();
        // The pass waits on memory: for the source it reads and for the line of the partition
        // it writes to. Fetching both ahead (the partition of the pair 16 ahead) took the update
        // from 28.2-28.7 to 27.8-28.0 ms at 1M boxes.
        constexpr std::size_t kAhead = 16;
        for (std::size_t i = 0; i < n; ++i) {
            if (i + 2 * kAhead < n) __builtin_prefetch(&source[i + 2 * kAhead]);
            if (i + kAhead < n) {
                const Pair& ahead = source[i + kAhead];
                __builtin_prefetch(out + end[partition_of(pack_pair(ahead.a, ahead.b & 0xFFFFFFFFU), new_bits)], 1);
            }
            const Pair& pair = source[i];
            if (pair.a >= pair.b || pair.b > 0xFFFFFFFFU) [[unlikely]] {
                if (pair.a >= pair.b) throw_unordered(source, i);
                make_empty();
                return false;
            }
            watch(pair, 0);
            const PackedPair word = pack_pair(pair.a, pair.b);  // its own hash
            const std::size_t p = partition_of(word, new_bits);
            if (end[p] < (p + 1) * room) [[likely]] {
                out[end[p]++] = word;
            } else {
                spill.push_back(word);
            }
        }
        std::sort(spill.begin(), spill.end());
        return true;
    }

    /// Counts, then scatters: partitions back to back, each thread its own contiguous share of
    /// `source`.
    template <class Watch>
    void assign_counted(std::span<const Pair> source, int threads, int new_bits, const Watch& watch) {
        const std::size_t parts = std::size_t{1} << new_bits;
        const std::size_t n = source.size();
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
                watch(pair, t);
                ++count[partition_of(pair_hash(pair), new_bits)];
            }
            names[static_cast<std::size_t>(t)] = seen;
        }
        for (const std::size_t i : first_bad) {
            if (i != SIZE_MAX) throw_unordered(source, i);
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
        starts.pop_back();
        const bool pack = all_names <= 0xFFFFFFFFU;
        if (pack) {
            resize_with_slack(packed, n);
        } else {
            resize_with_slack(wide, n);
        }
        begins.swap(starts);
        ends.assign(begins.begin() + 1, begins.end());
        ends.push_back(static_cast<std::uint32_t>(n));
        spill.clear();
        pair_count = n;
        gapped = false;
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
                    packed[cursor[partition_of(word, new_bits)]++] = word;
                }
            } else {
                for (std::size_t i = lo; i < hi; ++i)
                    wide[cursor[partition_of(pair_hash(source[i]), new_bits)]++] = source[i];
            }
        }
    }
};

}  // namespace smb::detail
