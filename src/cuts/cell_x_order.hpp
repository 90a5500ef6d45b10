// SPDX-License-Identifier: MIT
#pragma once
// The x order of a swept cell (a column, or a crowded cell where x is cut; cell_pairs.hpp): the
// keys (monotone 32-bit key of min x << 32 | local number) of the cell's boxes in increasing
// order, boxes of equal keys ordered by exact min x and id, and a bound on the boxes' x extent.

#include <algorithm>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "cuts/monotone_key.hpp"
#include "smb/box.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class CellXOrder {
public:
    /// The keys of the last sort(), in increasing order.
    [[nodiscard]] const std::uint64_t* keys() const noexcept { return order_.data(); }
    [[nodiscard]] std::size_t size() const noexcept { return order_.size(); }
    /// About how many boxes a row of the last sort() reaches along x, at most: the boxes times
    /// the widest extent over the span of the min x (a crowd on one x: all of them).
    [[nodiscard]] double reach() const noexcept { return reach_; }
    /// At least every box's max x - min x in the last sort().
    [[nodiscard]] Real widest_x() const noexcept { return widest_x_; }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return (order_.capacity() + spread_.capacity()) * sizeof(std::uint64_t) + xs_.capacity() * sizeof(float) +
               (bucket_.capacity() + bucket_count_.capacity()) * sizeof(std::uint32_t);
    }

    // Boxes whose keys are equal arrive in an order that depends on the previous step; ordering
    // them by exact coordinate and id makes the reported order a function of the boxes alone,
    // so that detecting twice without changes reports the same list. Such runs are rare outside
    // scenes of equal coordinates, where they are short.
    template <class Id>
    void order_equal_keys(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                          std::span<const Id> ids) {
        if (!shared_keys_) return;
        std::uint64_t* order = order_.data();
        const std::size_t m = order_.size();
        std::size_t run = 0;
        for (std::size_t i = 1; i <= m; ++i) {
            if (i < m && (order[i] >> 32) == (order[run] >> 32)) continue;
            if (i - run > 1) {
                std::sort(order + run, order + i, [&](std::uint64_t x, std::uint64_t y) {
                    const std::uint32_t a = entries[x & 0xFFFFFFFFU];
                    const std::uint32_t b = entries[y & 0xFFFFFFFFU];
                    if (boxes[a].min[0] != boxes[b].min[0]) return boxes[a].min[0] < boxes[b].min[0];
                    return ids[a] < ids[b];
                });
            }
            run = i;
        }
    }

    // Writes to order_ the cell's keys in increasing order and returns the insertion-sort moves.
    // The list follows last step's order, so a cell's boxes come as a few sorted runs interleaved
    // in x, one from each cell they were at home in. So a counting pass first spreads the keys
    // over about m buckets of equal width in x, leaving each box among the few of its bucket, and
    // DIS with the single increment 1 sorts those. A cell whose keys crowd into a few buckets
    // stops the insertions past a bound and is sorted outright: the same sorted list either way.
    std::size_t sort(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes) {
        const std::size_t m = entries.size();
        order_.resize(m);
        shared_keys_ = false;
        reach_ = 0;
        if (m == 0) return 0;
        spread_.resize(m);
        bucket_.resize(m);
        xs_.resize(m);
        std::uint64_t* keyed = spread_.data();
        float* xs = xs_.data();
        // The bounds are kept as integers, keys and the bits of extents (never negative, so
        // ordered as their bits): a float min or max would chain every entry to the one before
        // by its latency, where integer ones take a cycle.
        std::uint32_t lowest_key = ~std::uint32_t{0};
        std::uint32_t highest_key = 0;
        ExtentBits widest = 0;
        for (std::size_t i = 0; i < m; ++i) {
            const Box<Real, Dim>& box = boxes[entries[i]];
            const Real x = box.min[0];
            xs[i] = to_float(x);
            const std::uint32_t key = monotone_key(x);
            lowest_key = std::min(lowest_key, key);
            highest_key = std::max(highest_key, key);
            widest = std::max(widest, std::bit_cast<ExtentBits>(static_cast<Real>(box.max[0] - x)));
            keyed[i] = (std::uint64_t{key} << 32) | i;
        }
        // At most every rounded min (a key of double input is the next float down where the
        // rounding went up), so no bucket below is negative; the top bucket is clamped.
        const float lo = float_of_key(lowest_key);
        const float hi = float_of_key(highest_key);
        // Rounded up: no box's exact extent exceeds it.
        widest_x_ = std::nextafter(std::bit_cast<Real>(widest), std::numeric_limits<Real>::infinity());
        // Buckets by the rounded value, which never reverses an order: keys in increasing order
        // fall in buckets that never decrease, so each bucket is one stretch of the sorted list.
        const std::size_t buckets = m;
        // Rounded float arithmetic is monotone too. A width beyond the float range puts every
        // box in one bucket (the bound then sorts them outright).
        const float width = hi - lo;
        reach_ = width > 0 ? static_cast<double>(m) * static_cast<double>(widest_x_) / static_cast<double>(width)
                           : static_cast<double>(m);
        // So does a subnormal width, whose scale would overflow float (and 0 * infinity is NaN).
        const double raw_scale = width > 0 && width < std::numeric_limits<float>::infinity()
                                     ? static_cast<double>(buckets) / static_cast<double>(width)
                                     : 0.0;
        const float scale =
            raw_scale < static_cast<double>(std::numeric_limits<float>::max()) ? static_cast<float>(raw_scale) : 0.0F;
        const auto last_bucket = static_cast<float>(buckets - 1);
        bucket_count_.assign(buckets + 1, 0U);
        std::uint32_t* bucket = bucket_.data();
        std::uint32_t* count = bucket_count_.data();
        for (std::size_t i = 0; i < m; ++i) {
            // With scale 0 the difference may itself overflow to infinity, and infinity * 0 is NaN.
            const float position = scale > 0 ? (xs[i] - lo) * scale : 0.0F;
            bucket[i] = static_cast<std::uint32_t>(std::min(position, last_bucket));
            ++count[bucket[i] + 1];
        }
        for (std::size_t b = 0; b < buckets; ++b) count[b + 1] += count[b];
        std::uint64_t* order = order_.data();
        for (std::size_t i = 0; i < m; ++i) order[count[bucket[i]]++] = keyed[i];
        return insertion_sort(order, m, 8 * m + 64);
    }

private:
    using ExtentBits = std::conditional_t<sizeof(Real) == 8, std::uint64_t, std::uint32_t>;

    // DIS with the single increment 1 on a list whose boxes lie close to their places. Past
    // `bound` moves the rest is sorted outright. The keys carry the local numbers, so a move
    // shifts 8 bytes, not a box. The last key placed is held in a register: read back from the
    // list, each entry would wait on the store of the one before. Notes whether two boxes share
    // a key (order_equal_keys()): an entry placed lands after the keys equal to its own.
    std::size_t insertion_sort(std::uint64_t* keys, std::size_t m, std::size_t bound) {
        std::size_t moves = 0;
        bool shared = false;
        std::uint64_t last = keys[0];
        for (std::size_t i = 1; i < m; ++i) {
            const std::uint64_t moving = keys[i];
            if (moving >= last) {
                shared |= (moving >> 32) == (last >> 32);
                last = moving;
                continue;
            }
            std::size_t j = i;
            do {
                keys[j] = keys[j - 1];
                --j;
            } while (j > 0 && moving < keys[j - 1]);
            keys[j] = moving;
            shared |= j > 0 && (moving >> 32) == (keys[j - 1] >> 32);
            moves += i - j;
            shared |= (keys[j + 1] >> 32) == (moving >> 32);
            if (moves > bound) {
                std::sort(keys, keys + m);
                shared = true;  // not looked for
                break;
            }
        }
        shared_keys_ = shared;
        return moves;
    }

    std::vector<std::uint64_t> order_;
    Real widest_x_ = 0;                        // see widest_x()
    double reach_ = 0;                         // see reach()
    bool shared_keys_ = false;                 // two boxes of the last sort() share a key
    std::vector<std::uint64_t> spread_;        // the keys in the order of the entries
    std::vector<std::uint32_t> bucket_;        // the bucket of each entry
    std::vector<float> xs_;                    // the min x of each entry, rounded to float
    std::vector<std::uint32_t> bucket_count_;  // the counting pass's offsets
};

}  // namespace smb::detail
