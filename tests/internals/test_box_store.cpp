// SPDX-License-Identifier: MIT
// The box store's compaction (src/core/box_store.hpp, src/core/slot_renumbering.hpp): under random
// inserts and removals, with any number of slots listed by a pipeline, every old slot is mapped
// to the slot its box now has (or to none, removed), the listed survivors keep the first slots,
// the arrivals follow in their order, and only as many listed boxes move as were removed.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "core/box_store.hpp"

namespace smb::detail {
namespace {

using Store = BoxStore<double, 3>;

Box<double, 3> box_of(BoxId id) {
    const auto x = static_cast<double>(id);
    return Box<double, 3>{{x, 0, 0}, {x + 1, 1, 1}};
}

TEST(BoxStoreCompaction, RenumbersEverySlotAndMovesFewBoxes) {
    std::mt19937_64 random(17);
    Store store;
    BoxId next_id = 0;
    std::size_t listed = 0;  // as a pipeline would: every slot after each compaction
    for (int round = 0; round < 300; ++round) {
        SCOPED_TRACE(round);
        // Arrivals and removals since the last "detection", removals among both.
        const std::size_t arrivals = random() % 40;
        for (std::size_t i = 0; i < arrivals; ++i) {
            const BoxId id = next_id++ * 3 + 1;  // sparse enough to use the index's hash map too
            const Box<double, 3> box = box_of(id);
            store.insert(std::span(&id, 1), std::span(&box, 1));
        }
        std::vector<BoxId> doomed;
        for (Slot slot = 0; slot < store.slot_count(); ++slot) {
            if (random() % 5 == 0) doomed.push_back(store.id_at(slot));
        }
        store.remove(doomed);
        // A pipeline may list fewer slots than were there at the last compaction (a new one).
        const std::size_t claimed = random() % 8 == 0 ? listed / 2 : listed;

        std::vector<BoxId> id_before(store.slot_count());
        std::vector<bool> alive_before(store.slot_count());
        for (Slot slot = 0; slot < store.slot_count(); ++slot) {
            id_before[slot] = store.id_at(slot);
            alive_before[slot] = store.alive(slot);
        }
        const std::size_t removed_listed = [&] {
            std::size_t count = 0;
            for (std::size_t s = 0; s < claimed; ++s) count += alive_before[s] ? 0 : 1;
            return count;
        }();

        const SlotRenumbering renumbering = store.compact(claimed);
        ASSERT_EQ(renumbering.old_count(), id_before.size());
        ASSERT_FALSE(store.has_removals());
        std::size_t survivors = 0;
        std::size_t moved_listed = 0;
        std::vector<bool> taken(store.slot_count(), false);
        for (Slot old = 0; old < id_before.size(); ++old) {
            const Slot now = renumbering(old);
            if (!alive_before[old]) {
                EXPECT_EQ(now, kNoSlot) << "old slot " << old;
                continue;
            }
            ++survivors;
            ASSERT_LT(now, store.slot_count()) << "old slot " << old;
            EXPECT_FALSE(taken[now]) << "new slot " << now << " taken twice";
            taken[now] = true;
            EXPECT_EQ(store.id_at(now), id_before[old]);
            EXPECT_EQ(store.slot_of(id_before[old]), now);
            EXPECT_EQ(store.box_at(now).min[0], box_of(id_before[old]).min[0]);
            if (old < claimed) {
                EXPECT_LT(now, claimed - removed_listed) << "a listed box left the first slots";
                moved_listed += now != old ? 1 : 0;
            } else {
                EXPECT_GE(now, claimed - removed_listed) << "an arrival took a listed box's slot";
            }
        }
        EXPECT_EQ(survivors, store.slot_count());
        EXPECT_EQ(survivors, store.size());
        EXPECT_LE(moved_listed, removed_listed);
        // Past the old slots, nothing maps anywhere.
        EXPECT_EQ(renumbering(static_cast<Slot>(id_before.size())), kNoSlot);
        listed = store.slot_count();
    }
}

TEST(BoxStoreCompaction, ArrivalsKeepTheirOrder) {
    Store store;
    for (BoxId id = 0; id < 10; ++id) {
        const Box<double, 3> box = box_of(id);
        store.insert(std::span(&id, 1), std::span(&box, 1));
    }
    const std::vector<BoxId> gone{1, 2, 6, 8};
    store.remove(gone);
    // Slots 0-4 listed: 1 and 2 were listed and take the living listed boxes 3 and 4; the
    // arrivals 5, 7, 9 close up behind in their order.
    const SlotRenumbering renumbering = store.compact(5);
    std::vector<BoxId> now;
    for (Slot slot = 0; slot < store.slot_count(); ++slot) now.push_back(store.id_at(slot));
    EXPECT_EQ(now, (std::vector<BoxId>{0, 3, 4, 5, 7, 9}));
    EXPECT_EQ(renumbering(1), kNoSlot);
    EXPECT_EQ(renumbering(3), 1U);
    EXPECT_EQ(renumbering(4), 2U);
    EXPECT_EQ(renumbering(5), 3U);
    EXPECT_EQ(renumbering(6), kNoSlot);
    EXPECT_EQ(renumbering(9), 5U);
}

}  // namespace
}  // namespace smb::detail
