// SPDX-License-Identifier: MIT
// The arrays that follow the number of boxes (src/core/bulk_vector.hpp): small blocks come from
// the plain allocator as they are, large ones have their pages mapped first; either way a
// BulkVector keeps its contents through growth, copies, moves and swaps across the threshold, as
// std::vector does.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <new>
#include <numeric>
#include <utility>
#include <vector>

#include "core/bulk_vector.hpp"
#include "core/tuning.hpp"

namespace smb::detail {
namespace {

constexpr std::size_t kLargeFloats = tuning::mapped_at_once_from / sizeof(float);

TEST(BulkVectorTest, LargeBlocksAreWhole) {
    MappedAllocator<float> allocator;
    for (const std::size_t n : {kLargeFloats - 1, kLargeFloats, kLargeFloats + 1, 3 * kLargeFloats + 7}) {
        float* block = allocator.allocate(n);
        ASSERT_NE(block, nullptr);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(block) % alignof(float), 0U);
        block[0] = 1;
        block[n - 1] = 2;  // the whole block is usable, the part before its first page included
        EXPECT_EQ(block[0] + block[n - 1], 3);
        allocator.deallocate(block, n);
    }
}

TEST(BulkVectorTest, SmallBlocksComeFromThePlainAllocator) {
    MappedAllocator<double> allocator;
    double* block = allocator.allocate(1000);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(block) % alignof(double), 0U);
    block[999] = 4;
    EXPECT_EQ(block[999], 4);
    allocator.deallocate(block, 1000);
}

TEST(BulkVectorTest, RefusesASizeBeyondTheAddressSpace) {
    MappedAllocator<std::uint64_t> allocator;
    EXPECT_THROW((void)allocator.allocate(std::numeric_limits<std::size_t>::max() / 4), std::bad_array_new_length);
}

TEST(BulkVectorTest, KeepsItsContentsWhileGrowingPastTheThresholdAndBack) {
    BulkVector<std::uint32_t> values;
    std::vector<std::uint32_t> reference;
    // One element at a time over the threshold: every reallocation moves the contents from a
    // small block to a large one, or between large ones.
    for (std::uint32_t i = 0; i < 3 * tuning::mapped_at_once_from / sizeof(std::uint32_t); i += 7) {
        values.push_back(i);
        reference.push_back(i);
    }
    ASSERT_EQ(values.size(), reference.size());
    EXPECT_TRUE(std::equal(values.begin(), values.end(), reference.begin()));
    values.resize(10);
    values.shrink_to_fit();  // back to a small block
    EXPECT_TRUE(std::equal(values.begin(), values.end(), reference.begin()));
}

TEST(BulkVectorTest, CopiesMovesAndSwapsLikeAVector) {
    BulkVector<float> large(kLargeFloats + 100);
    std::iota(large.begin(), large.end(), 0.0F);
    BulkVector<float> small{1, 2, 3};
    BulkVector<float> copy = large;
    EXPECT_EQ(copy, large);
    EXPECT_NE(copy.data(), large.data());
    copy.swap(small);
    EXPECT_EQ(small, large);
    EXPECT_EQ(copy, (BulkVector<float>{1, 2, 3}));
    const float* block = large.data();
    BulkVector<float> moved = std::move(large);
    EXPECT_EQ(moved.data(), block);  // a move takes the block: the allocators are equal
    EXPECT_EQ(moved, small);
}

}  // namespace
}  // namespace smb::detail
