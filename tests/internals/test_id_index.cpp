// SPDX-License-Identifier: MIT
// The id index (src/core/id_index.hpp): small ids in an array, the others in a hash map, checked
// against std::map under random inserts, moves and erases of dense, sparse and mixed ids.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include "core/id_index.hpp"

namespace smb::detail {
namespace {

void expect_same(const IdIndex& index, const std::map<BoxId, Slot>& reference) {
    ASSERT_EQ(index.size(), reference.size());
    for (const auto& [id, slot] : reference) ASSERT_EQ(index.find(id), slot) << "id " << id;
    std::map<BoxId, Slot> visited;
    index.for_each([&](BoxId id, Slot slot) { EXPECT_TRUE(visited.emplace(id, slot).second) << "id " << id; });
    EXPECT_EQ(visited, reference);
}

// Ids drawn by `draw`, inserted, moved and erased at random for a few thousand rounds.
template <class Draw>
void churn(std::uint64_t seed, Draw draw) {
    std::mt19937_64 random(seed);
    IdIndex index;
    std::map<BoxId, Slot> reference;
    std::vector<BoxId> present;
    for (int round = 0; round < 20000; ++round) {
        const auto action = random() % 10;
        if (action < 6 || present.empty()) {
            const BoxId id = draw(random);
            const auto slot = static_cast<Slot>(random() % 1000000);
            const bool fresh = !reference.contains(id);
            ASSERT_EQ(index.insert(id, slot), fresh) << "id " << id;
            if (fresh) {
                reference.emplace(id, slot);
                present.push_back(id);
            }
        } else if (action < 8) {
            const BoxId id = present[random() % present.size()];
            const auto slot = static_cast<Slot>(random() % 1000000);
            index.move(id, slot);
            reference[id] = slot;
        } else {
            const std::size_t at = random() % present.size();
            const BoxId id = present[at];
            present[at] = present.back();
            present.pop_back();
            index.erase(id);
            reference.erase(id);
            ASSERT_EQ(index.find(id), kNoSlot);
        }
    }
    expect_same(index, reference);
}

TEST(IdIndex, DenseIdsAgreeWithAMap) {
    churn(1, [](std::mt19937_64& random) { return BoxId{random() % 5000}; });
}

TEST(IdIndex, SparseIdsAgreeWithAMap) {
    churn(2, [](std::mt19937_64& random) { return BoxId{random()}; });
}

TEST(IdIndex, MixedIdsAgreeWithAMap) {
    churn(3, [](std::mt19937_64& random) { return random() % 4 == 0 ? BoxId{random()} : BoxId{random() % 20000}; });
}

TEST(IdIndex, IdsJustAboveTheArrayMoveIntoItAsItGrows) {
    IdIndex index;
    // 5000 lies beyond the array while the index is small, so it starts in the hash map.
    ASSERT_TRUE(index.insert(5000, 7));
    for (BoxId id = 0; id < 4000; ++id) ASSERT_TRUE(index.insert(id, static_cast<Slot>(id)));
    EXPECT_EQ(index.find(5000), 7U);
    EXPECT_FALSE(index.insert(5000, 8));
    EXPECT_EQ(index.find(5000), 7U);
    index.erase(5000);
    EXPECT_EQ(index.find(5000), kNoSlot);
    EXPECT_EQ(index.size(), 4000U);
}

TEST(IdIndex, ExtremeIdsAndClear) {
    IdIndex index;
    const BoxId top = std::numeric_limits<BoxId>::max();
    ASSERT_TRUE(index.insert(top, 1));
    ASSERT_TRUE(index.insert(0, 2));
    ASSERT_TRUE(index.insert(top - 1, 3));
    EXPECT_FALSE(index.insert(top, 4));
    EXPECT_EQ(index.find(top), 1U);
    EXPECT_EQ(index.find(top - 1), 3U);
    EXPECT_EQ(index.find(0), 2U);
    EXPECT_EQ(index.find(1), kNoSlot);
    index.clear();
    EXPECT_EQ(index.size(), 0U);
    EXPECT_EQ(index.find(top), kNoSlot);
    EXPECT_EQ(index.bytes_held(), 0U);
}

TEST(IdIndex, DenseIdsCostFourBytesEachAndSparseIdsNeverGrowTheArray) {
    IdIndex dense;
    for (BoxId id = 0; id < 100000; ++id) dense.insert(id, static_cast<Slot>(id));
    EXPECT_LE(dense.bytes_held(), 2 * 100000 * sizeof(Slot));
    IdIndex sparse;
    for (BoxId i = 0; i < 1000; ++i) sparse.insert((i + 1) << 32, static_cast<Slot>(i));
    // The array would need 2^42 entries: every id is in the hash map.
    EXPECT_LT(sparse.bytes_held(), 1000 * 64);
}

TEST(IdIndex, ABatchReservedAtOnceHoldsItsIdsInOneArrayAndMovesTheMapsIdsIn) {
    IdIndex index;
    // 3000 starts in the hash map; the batch's reserve grows the array past it, once.
    ASSERT_TRUE(index.insert(3000, 9));
    std::map<BoxId, Slot> reference{{3000, 9}};
    index.reserve(2500, 2499 + 1000);
    EXPECT_EQ(index.find(3000), 9U);
    const std::size_t reserved = index.bytes_held();
    for (BoxId id = 1000; id < 3500; ++id) {
        if (id == 3000) continue;
        ASSERT_TRUE(index.insert(id, static_cast<Slot>(id)));
        reference.emplace(id, static_cast<Slot>(id));
    }
    EXPECT_EQ(index.bytes_held(), reserved) << "no id of the batch grew the array again";
    EXPECT_LE(reserved, 3500 * sizeof(Slot) + 256) << "the array and the hash map's few buckets";
    expect_same(index, reference);
    // A largest id beyond twice the boxes stays out of the array, as it would one by one.
    index.reserve(1, BoxId{1} << 40);
    EXPECT_EQ(index.bytes_held(), reserved);
    ASSERT_TRUE(index.insert(BoxId{1} << 40, 1));
    reference.emplace(BoxId{1} << 40, 1);
    expect_same(index, reference);
}

}  // namespace
}  // namespace smb::detail
