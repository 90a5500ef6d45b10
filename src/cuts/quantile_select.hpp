// SPDX-License-Identifier: MIT
#pragma once
// The quantiles of the axial cut: the keys of ranks floor(j n / k), j = 1 .. k-1, of n keys.
//
// A group of a cold cut holds about 24 registrations per segment (the target cell population),
// so k is large against n / k: in 2D at 1M boxes a slab of ~5000 keys is cut into 204 columns,
// in 3D a column of ~1500 into 35 cells. Selecting the quantiles by recursive selection costs
// O(n log k) comparisons, half of them branch misses on keys in no order; an LSD radix sort of
// the keys' bit images costs a few linear passes with no data-dependent branch, and then every
// quantile is a read. Both return the same values (the key of a given rank is unique), so the
// planes do not depend on which one ran.

#include <algorithm>
#include <array>
#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/tuning.hpp"

namespace smb::detail {

/// The unsigned integer as wide as Real, whose order on radix_key() images is Real's order.
template <std::floating_point Real>
using RadixKey = std::conditional_t<sizeof(Real) == 4, std::uint32_t, std::uint64_t>;

/// Bit image of a key that sorts as the key does: positives get the sign bit set, negatives are
/// complemented. -0 sorts just below +0, which compare equal, so no plane depends on it.
template <std::floating_point Real>
[[nodiscard]] inline RadixKey<Real> radix_key(Real value) noexcept {
    using Key = RadixKey<Real>;
    constexpr Key sign = Key{1} << (8 * sizeof(Key) - 1);
    const auto bits = std::bit_cast<Key>(value);
    return (bits & sign) != 0 ? static_cast<Key>(~bits) : static_cast<Key>(bits | sign);
}

template <std::floating_point Real>
[[nodiscard]] inline Real from_radix_key(RadixKey<Real> key) noexcept {
    using Key = RadixKey<Real>;
    constexpr Key sign = Key{1} << (8 * sizeof(Key) - 1);
    return std::bit_cast<Real>((key & sign) != 0 ? static_cast<Key>(key & ~sign) : static_cast<Key>(~key));
}

/// Selects the quantiles of `keys`, which the caller fills. Holds its buffers from one cut to
/// the next, so that cutting again in a steady step allocates nothing; one per thread.
template <std::floating_point Real>
class QuantileSelector {
public:
    /// The keys of the group being cut; select() reorders them.
    std::vector<Real> keys;

    /// Below this many keys the recursive selection is faster.
    static constexpr std::size_t kRadixFrom = tuning::quantile_radix_from;

    /// out[j-1] = the key of rank min(n-1, floor(j n / segments)) for j in [1, segments).
    void select(std::uint32_t segments, Real* out) {
        if (keys.size() < kRadixFrom) {
            select_by_selection(segments, out);
        } else {
            select_by_radix_sort(segments, out);
        }
    }

    /// The two ways, each for any number of keys (select() picks one; tests and
    /// bench/bench_quantiles.cpp drive both).
    void select_by_selection(std::uint32_t segments, Real* out) {
        if (segments < 2 || keys.empty()) return;
        select_recursively(0, keys.size(), 1, segments, segments, out);
    }
    void select_by_radix_sort(std::uint32_t segments, Real* out) {
        const std::size_t n = keys.size();
        if (segments < 2 || n == 0) return;
        const Key* sorted = radix_sort();
        for (std::uint32_t j = 1; j < segments; ++j) out[j - 1] = from_radix_key<Real>(sorted[rank_of(j, n, segments)]);
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return keys.capacity() * sizeof(Real) + (images_.capacity() + spare_.capacity()) * sizeof(Key);
    }

private:
    using Key = RadixKey<Real>;
    static constexpr int kDigitBits = 8;
    static constexpr std::size_t kDigits = sizeof(Key);
    static constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;

    [[nodiscard]] static std::size_t rank_of(std::uint32_t j, std::size_t n, std::uint32_t segments) noexcept {
        return std::min(n - 1, (static_cast<std::size_t>(j) * n) / segments);
    }

    // The key of rank r(middle) first, then either side of it: each depth of the recursion is
    // one linear pass, O(n log k) in all.
    void select_recursively(std::size_t from, std::size_t to, std::uint32_t first_j, std::uint32_t last_j,
                            std::uint32_t segments, Real* out) {
        if (first_j >= last_j) return;
        const std::uint32_t middle_j = first_j + (last_j - first_j) / 2;
        const std::size_t rank = rank_of(middle_j, keys.size(), segments);
        std::nth_element(keys.begin() + static_cast<std::ptrdiff_t>(from),
                         keys.begin() + static_cast<std::ptrdiff_t>(rank),
                         keys.begin() + static_cast<std::ptrdiff_t>(to));
        out[middle_j - 1] = keys[rank];
        // Ranks may repeat when n < k: both sides keep the selected place.
        select_recursively(from, rank + 1, first_j, middle_j, segments, out);
        select_recursively(rank, to, middle_j + 1, last_j, segments, out);
    }

    /// Least significant digit first, one counting pass for all digits; a digit every key
    /// shares (the high bytes of keys in a narrow range) is skipped.
    const Key* radix_sort() {
        const std::size_t n = keys.size();
        images_.resize(n);
        spare_.resize(n);
        std::array<std::array<std::uint32_t, kBuckets>, kDigits> count{};
        for (std::size_t i = 0; i < n; ++i) {
            const Key image = radix_key(keys[i]);
            images_[i] = image;
            for (std::size_t d = 0; d < kDigits; ++d) ++count[d][(image >> (kDigitBits * d)) & (kBuckets - 1)];
        }
        Key* from = images_.data();
        Key* to = spare_.data();
        for (std::size_t d = 0; d < kDigits; ++d) {
            std::array<std::uint32_t, kBuckets>& offset = count[d];
            if (std::find(offset.begin(), offset.end(), static_cast<std::uint32_t>(n)) != offset.end()) continue;
            std::uint32_t sum = 0;
            for (std::uint32_t& bucket : offset) sum += std::exchange(bucket, sum);
            for (std::size_t i = 0; i < n; ++i) {
                const Key image = from[i];
                to[offset[(image >> (kDigitBits * d)) & (kBuckets - 1)]++] = image;
            }
            std::swap(from, to);
        }
        return from;
    }

    std::vector<Key> images_;
    std::vector<Key> spare_;
};

}  // namespace smb::detail
