// SPDX-License-Identifier: MIT
// The membership of interaction classes (src/filters/class_members.hpp), checked against a plain
// array of classes under random moves, swap-removes and resizes: every position is a member of
// its class exactly once, at the index it holds, and a member that stays keeps its index.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "filters/class_members.hpp"

namespace smb::detail {
namespace {

constexpr std::size_t kClasses = 5;

void expect_same(const ClassMembers& members, const std::vector<std::uint8_t>& reference) {
    std::vector<int> seen(reference.size(), 0);
    for (std::size_t c = 0; c < kClasses; ++c) {
        for (const std::uint32_t p : members.members(c)) {
            ASSERT_LT(p, reference.size());
            EXPECT_EQ(reference[p], c) << "position " << p;
            ++seen[p];
        }
    }
    for (std::size_t p = 0; p < reference.size(); ++p) {
        EXPECT_EQ(members.class_of(p), reference[p]) << "position " << p;
        EXPECT_EQ(seen[p], reference[p] == ClassMembers::kNone ? 0 : 1) << "position " << p;
    }
}

// The index of position p among the members of its class.
std::size_t index_of(const ClassMembers& members, std::size_t p) {
    const auto list = members.members(members.class_of(p));
    for (std::size_t k = 0; k < list.size(); ++k)
        if (list[k] == p) return k;
    return list.size();
}

TEST(ClassMembers, RandomMovesSwapRemovesAndResizesMatchAPlainArray) {
    std::mt19937_64 random(36);
    ClassMembers members;
    members.reset(kClasses);
    std::vector<std::uint8_t> reference;
    auto draw_class = [&] {
        const auto c = random() % (kClasses + 1);
        return c == kClasses ? ClassMembers::kNone : static_cast<std::uint8_t>(c);
    };
    for (int round = 0; round < 20000; ++round) {
        const auto action = random() % 10;
        if (action < 4 || reference.empty()) {  // a new position joins
            const std::uint8_t c = draw_class();
            members.move(reference.size(), c);
            reference.push_back(c);
        } else if (action < 7) {  // a position changes class; the other members keep their index
            const std::size_t p = random() % reference.size();
            const std::uint8_t c = draw_class();
            const std::size_t other = random() % reference.size();
            const bool stays = other != p && reference[other] != ClassMembers::kNone &&
                               (reference[other] != reference[p] || reference[p] == c);
            const std::size_t before = stays ? index_of(members, other) : 0;
            members.move(p, c);
            reference[p] = c;
            if (stays) {
                EXPECT_EQ(index_of(members, other), before);
            }
        } else if (action < 9) {  // swap-removed: the last position now sits at p
            const std::size_t p = random() % reference.size();
            members.swap_remove(p, reference.size() - 1);
            reference[p] = reference.back();
            reference.pop_back();
        } else {  // the array shrinks or grows
            const std::size_t size = random() % (reference.size() + 8);
            members.resize(size);
            reference.resize(size, ClassMembers::kNone);
        }
        ASSERT_NO_FATAL_FAILURE(expect_same(members, reference)) << "round " << round;
    }
}

TEST(ClassMembers, ResetEmptiesEveryClassAndForgetsThePositions) {
    ClassMembers members;
    members.reset(2);
    members.move(0, 1);
    members.move(3, 0);
    members.reset(3);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_TRUE(members.members(c).empty());
    members.resize(2);
    EXPECT_EQ(members.class_of(0), ClassMembers::kNone);
    EXPECT_EQ(members.class_of(1), ClassMembers::kNone);
}

}  // namespace
}  // namespace smb::detail
