// SPDX-License-Identifier: MIT
// The quantiles of the axial cut (src/cuts/quantile_select.hpp): the radix sort and the recursive
// selection must return the key of every rank floor(j n / k) exactly, as a full sort does, for
// any keys: negatives, signed zeros, long runs of equal keys, the ends of the range.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "cuts/quantile_select.hpp"

namespace smb::detail {
namespace {

template <class Real>
class QuantileSelect : public ::testing::Test {};
using Reals = ::testing::Types<float, double>;
TYPED_TEST_SUITE(QuantileSelect, Reals);

/// The quantiles as a full sort gives them.
template <class Real>
std::vector<Real> sorted_quantiles(std::vector<Real> keys, std::uint32_t segments) {
    std::sort(keys.begin(), keys.end());
    std::vector<Real> out;
    for (std::uint32_t j = 1; j < segments; ++j)
        out.push_back(keys[std::min(keys.size() - 1, (static_cast<std::size_t>(j) * keys.size()) / segments)]);
    return out;
}

/// Keys of one of several shapes: spread, clustered, few distinct values, the extremes of Real.
template <class Real>
std::vector<Real> make_keys(std::size_t n, int shape, std::mt19937_64& random) {
    constexpr Real top = std::numeric_limits<Real>::max();
    std::uniform_real_distribution<Real> wide(-1000, 1000);
    std::normal_distribution<Real> narrow(static_cast<Real>(5e3), static_cast<Real>(1e-2));
    const Real specials[] = {Real{0},
                             -Real{0},
                             top,
                             -top,
                             std::numeric_limits<Real>::denorm_min(),
                             -std::numeric_limits<Real>::denorm_min(),
                             std::numeric_limits<Real>::infinity(),
                             -std::numeric_limits<Real>::infinity(),
                             Real{1},
                             Real{-1}};
    std::vector<Real> keys(n);
    for (Real& key : keys) {
        switch (shape) {
            case 0:
                key = wide(random);
                break;
            case 1:
                key = narrow(random);
                break;  // the high bytes all equal
            case 2:
                key = static_cast<Real>(random() % 7) - Real{3};
                break;  // runs of equal keys
            default:
                key = specials[random() % std::size(specials)];
                break;  // signed zeros, infinities
        }
    }
    return keys;
}

TYPED_TEST(QuantileSelect, EveryQuantileIsTheKeyOfItsRank) {
    using Real = TypeParam;
    std::mt19937_64 random(17);
    const std::size_t sizes[] = {
        1, 2, 5, 100, QuantileSelector<Real>::kRadixFrom - 1, QuantileSelector<Real>::kRadixFrom, 5000, 40000};
    QuantileSelector<Real> selector;  // one selector throughout: its buffers are reused
    for (const std::size_t n : sizes) {
        for (int shape = 0; shape < 4; ++shape) {
            for (const std::uint32_t segments : {2U, 7U, 35U, 204U, static_cast<std::uint32_t>(n + 3)}) {
                const std::vector<Real> keys = make_keys<Real>(n, shape, random);
                const std::vector<Real> expected = sorted_quantiles(keys, segments);
                // The way select() picks, then each way whatever the size.
                for (int way = 0; way < 3; ++way) {
                    selector.keys = keys;
                    std::vector<Real> out(segments - 1, std::numeric_limits<Real>::quiet_NaN());
                    if (way == 0) selector.select(segments, out.data());
                    if (way == 1) selector.select_by_selection(segments, out.data());
                    if (way == 2) selector.select_by_radix_sort(segments, out.data());
                    for (std::size_t j = 0; j < expected.size(); ++j) {
                        // == : a signed zero may come back as either zero, which are the same plane.
                        ASSERT_TRUE(out[j] == expected[j])
                            << "way " << way << ", n " << n << ", shape " << shape << ", segments " << segments
                            << ", quantile " << j + 1 << ": " << out[j] << " against " << expected[j];
                    }
                    ASSERT_TRUE(std::is_sorted(out.begin(), out.end()));
                }
            }
        }
    }
}

TYPED_TEST(QuantileSelect, TheRadixImageSortsAsTheKeysAndComesBackBitForBit) {
    using Real = TypeParam;
    std::mt19937_64 random(5);
    std::vector<Real> values;
    for (int shape = 0; shape < 4; ++shape) {
        const auto some = make_keys<Real>(200, shape, random);
        values.insert(values.end(), some.begin(), some.end());
    }
    for (const Real a : values) {
        EXPECT_EQ(std::bit_cast<RadixKey<Real>>(from_radix_key<Real>(radix_key(a))), std::bit_cast<RadixKey<Real>>(a));
        for (std::size_t i = 0; i < values.size(); i += 7) {
            const Real b = values[i];
            if (a < b) {
                EXPECT_LT(radix_key(a), radix_key(b));
            } else if (a > b) {
                EXPECT_GT(radix_key(a), radix_key(b));
            }
        }
    }
}

TYPED_TEST(QuantileSelect, NothingToSelectLeavesTheOutputAlone) {
    using Real = TypeParam;
    QuantileSelector<Real> selector;
    Real out[3] = {Real{9}, Real{9}, Real{9}};
    selector.select(4, out);  // no keys
    selector.keys = {Real{1}, Real{2}};
    selector.select(1, out);  // one segment: no plane
    EXPECT_EQ(out[0], Real{9});
    EXPECT_EQ(out[2], Real{9});
}

}  // namespace
}  // namespace smb::detail
