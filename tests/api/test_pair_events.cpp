// SPDX-License-Identifier: MIT
// PairEvents on its own: pair lists diffed against std::set_difference, over sizes that cross
// the partition layouts; replace, replace_all and swap_remove on small hand-made lists; bad
// input refused with everything left as it was.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <random>
#include <set>
#include <vector>

#include "reference/pair_sets.hpp"
#include "reference/world_types.hpp"
#include "smb/pair_events.hpp"

namespace smb::test {
namespace {

/// `count` distinct pairs among `names` names, in random order.
std::vector<Pair> random_pairs(std::mt19937_64& random, std::size_t count, BoxId names) {
    std::set<Pair> chosen;
    std::uniform_int_distribution<BoxId> name(0, names - 1);
    while (chosen.size() < count) {
        const BoxId a = name(random);
        const BoxId b = name(random);
        if (a != b) chosen.insert({std::min(a, b), std::max(a, b)});
    }
    std::vector<Pair> pairs(chosen.begin(), chosen.end());
    std::shuffle(pairs.begin(), pairs.end(), random);
    return pairs;
}

TEST(PairEvents, FirstUpdateBeginsEveryPair) {
    PairEvents events;
    EXPECT_TRUE(events.begun().empty());
    EXPECT_TRUE(events.ended().empty());
    const std::vector<Pair> pairs{{3, 9}, {1, 2}, {1, 7}};
    events.update(pairs);
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{1, 2}, {1, 7}, {3, 9}}));
    EXPECT_TRUE(events.ended().empty());
    EXPECT_EQ(events.size(), 3U);
    events.update(pairs);
    EXPECT_TRUE(events.begun().empty());
    EXPECT_TRUE(events.ended().empty());
    events.update({});
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{1, 2}, {1, 7}, {3, 9}}));
    EXPECT_EQ(events.size(), 0U);
}

TEST(PairEvents, RandomListsMatchSetDifference) {
    std::mt19937_64 random(41);
    PairEvents events;
    std::vector<Pair> previous;
    // Sizes up and down across several partition layouts, each list a mix of kept and new pairs.
    for (const std::size_t count :
         {std::size_t{0}, std::size_t{5}, std::size_t{3000}, std::size_t{2900}, scaled(40000), std::size_t{9000},
          scaled(70000), std::size_t{1}, std::size_t{0}, std::size_t{20000}}) {
        std::vector<Pair> next = random_pairs(random, count, 1 + count / 2 + 10);
        // Keep a random part of the previous list, as temporal coherence would.
        for (std::size_t i = 0; i < previous.size() && i < count / 2; i += 2) next[i] = previous[i];
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::shuffle(next.begin(), next.end(), random);
        events.update(next);
        EXPECT_EQ(as_vector(events.begun()), difference(next, previous)) << count;
        EXPECT_EQ(as_vector(events.ended()), difference(previous, next)) << count;
        EXPECT_EQ(events.size(), next.size());
        previous = next;
    }
}

TEST(PairEvents, ThreadsGiveTheSameEvents) {
    std::mt19937_64 random(47);
    PairEvents one;
    PairEvents four(4);
    EXPECT_EQ(four.threads(), 4U);
    std::vector<Pair> previous;
    // Enough pairs for four threads in each pass (64k pairs a thread at least).
    for (const std::size_t count : {140000, 270000}) {
        std::uniform_int_distribution<BoxId> name(0, count);
        std::vector<Pair> next;
        for (std::size_t i = 0; i < count; ++i) {
            const BoxId a = name(random);
            next.push_back({a, a + 1 + name(random) % 64});
        }
        for (std::size_t i = 0; i < previous.size() && i < count; i += 2) next[i] = previous[i];
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::shuffle(next.begin(), next.end(), random);
        one.update(next);
        four.update(next);
        EXPECT_EQ(as_vector(four.begun()), as_vector(one.begun()));
        EXPECT_EQ(as_vector(four.ended()), as_vector(one.ended()));
        previous = next;
    }
    // A pair kept and listed twice, far into the list: refused on any number of threads.
    std::vector<Pair> repeated = previous;
    repeated.push_back(previous[previous.size() / 2]);
    EXPECT_THROW(four.update(repeated), ArgumentError);
    std::vector<Pair> reversed = previous;
    std::swap(reversed.back().a, reversed.back().b);
    EXPECT_THROW(four.update(reversed), ArgumentError);
    EXPECT_EQ(four.size(), previous.size());
}

TEST(PairEvents, NamesBeyond32BitsAndBack) {
    // Lists whose names fit in 32 bits are held packed, others as they are; an update may cross
    // from one form to the other either way.
    std::mt19937_64 random(43);
    PairEvents events;
    std::vector<Pair> previous;
    for (int round = 0; round < 6; ++round) {
        const BoxId offset = round % 2 == 1 ? (BoxId{1} << 40) : 0;
        std::vector<Pair> next = random_pairs(random, 5000, 3000);
        for (std::size_t i = 0; i < next.size(); i += 3) next[i] = {next[i].a + offset, next[i].b + offset};
        for (std::size_t i = 1; i < previous.size() && i < next.size(); i += 3) next[i] = previous[i];
        if (round == 4) next.push_back({BoxId{1} << 63, ~BoxId{0}});
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::shuffle(next.begin(), next.end(), random);
        events.update(next);
        EXPECT_EQ(as_vector(events.begun()), difference(next, previous)) << round;
        EXPECT_EQ(as_vector(events.ended()), difference(previous, next)) << round;
        previous = next;
    }
}

TEST(PairEvents, EventsSortedWhenNamesFillAll32Bits) {
    // More events than the comparison sort takes, with names as wide as a packed pair allows:
    // the radix sort's key is then 64 bits of names, nothing to spare.
    std::mt19937_64 random(47);
    const BoxId top = BoxId{1} << 32;
    PairEvents events;
    std::vector<Pair> previous;
    for (int round = 0; round < 3; ++round) {
        std::vector<Pair> next = random_pairs(random, 9000, 4000);
        for (Pair& pair : next) pair = {top - 1 - pair.b, top - 1 - pair.a};
        events.update(next);
        EXPECT_EQ(as_vector(events.begun()), difference(next, previous)) << round;
        EXPECT_EQ(as_vector(events.ended()), difference(previous, next)) << round;
        previous = next;
    }
}

TEST(PairEvents, ReplacedNameEndsAndBeginsItsPairs) {
    PairEvents events;
    events.update(std::vector<Pair>{{1, 2}, {2, 3}, {4, 5}});
    events.replace(2);
    events.update(std::vector<Pair>{{1, 2}, {2, 6}, {4, 5}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{1, 2}, {2, 6}}));
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{1, 2}, {2, 3}}));
    // The calls are spent by the update that took them.
    events.update(std::vector<Pair>{{1, 2}, {2, 6}, {4, 5}});
    EXPECT_TRUE(events.begun().empty());
    EXPECT_TRUE(events.ended().empty());
    // The same through the overload, and replace_all.
    events.update(std::vector<Pair>{{1, 2}, {2, 6}, {4, 5}}, std::vector<BoxId>{5});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{4, 5}}));
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{4, 5}}));
    events.replace_all();
    events.update(std::vector<Pair>{{1, 2}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{1, 2}}));
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{1, 2}, {2, 6}, {4, 5}}));
}

TEST(PairEvents, SwapRemoveRenamesTheMovedBody) {
    // Bodies at 0..4; body 1 is removed, body 4 moves to 1.
    PairEvents events;
    events.update(std::vector<Pair>{{0, 1}, {1, 2}, {2, 4}, {3, 4}, {0, 3}});
    events.swap_remove(1, 4);
    // Body 4 (now 1) keeps its pairs with 2 and 3 and gains one with 0; body 1's pairs end.
    events.update(std::vector<Pair>{{1, 2}, {1, 3}, {0, 1}, {0, 3}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{0, 1}}));
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{0, 1}, {1, 2}}));
}

TEST(PairEvents, SwapRemovesCompose) {
    // Bodies A..F at 0..5. swap_remove(0, 5): F to 0. swap_remove(4, 4): E popped.
    // swap_remove(1, 3): D to 1. Then C at 2, F at 0, D at 1; one body G appended at 3.
    PairEvents events;
    events.update(std::vector<Pair>{{0, 1}, {2, 5}, {3, 5}, {4, 5}, {2, 3}, {1, 2}});
    events.swap_remove(0, 5);
    events.swap_remove(4, 4);
    events.swap_remove(1, 3);
    events.replace(3);  // harmless: index 3 holds no previous body any more
    // F-C (0,2) goes on; F-D (0,1) goes on; C-D (1,2) goes on; G-F (0,3) begins.
    events.update(std::vector<Pair>{{0, 2}, {0, 1}, {1, 2}, {0, 3}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{0, 3}}));
    // A-B (0,1), E-F (4,5) and B-C (1,2) end, under their previous names.
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{0, 1}, {1, 2}, {4, 5}}));
}

TEST(PairEvents, FatesOfLargeNames) {
    // Names past 2^27 take the hashed filter instead of one bit per name.
    const BoxId big = BoxId{1} << 40;
    PairEvents events;
    events.update(std::vector<Pair>{{big + 1, big + 2}, {big + 2, big + 3}, {big + 4, big + 5}, {3, 4}});
    events.replace(big + 2);
    events.swap_remove(big + 4, big + 9);  // nothing was at big + 9: big + 4 is gone
    events.update(std::vector<Pair>{{big + 1, big + 2}, {big + 2, big + 6}, {3, 4}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{big + 1, big + 2}, {big + 2, big + 6}}));
    EXPECT_EQ(as_vector(events.ended()),
              (std::vector<Pair>{{big + 1, big + 2}, {big + 2, big + 3}, {big + 4, big + 5}}));
}

TEST(PairEvents, SwapRemovingTheMovedBodyAgain) {
    // A B C D at 0..3: swap_remove(2, 3) moves D to 2, swap_remove(2, 2) pops D.
    PairEvents events;
    events.update(std::vector<Pair>{{0, 3}, {1, 2}, {0, 1}});
    events.swap_remove(2, 3);
    events.swap_remove(2, 2);
    events.update(std::vector<Pair>{{0, 1}});
    EXPECT_TRUE(events.begun().empty());
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{0, 3}, {1, 2}}));
}

TEST(PairEvents, BadInputChangesNothing) {
    PairEvents events;
    events.update(std::vector<Pair>{{1, 2}, {2, 3}});
    events.update(std::vector<Pair>{{1, 2}, {4, 5}});
    events.replace(1);
    const auto begun = as_vector(events.begun());
    const auto ended = as_vector(events.ended());
    EXPECT_THROW(events.update(std::vector<Pair>{{1, 2}, {3, 3}}), ArgumentError);
    EXPECT_THROW(events.update(std::vector<Pair>{{5, 4}}), ArgumentError);
    EXPECT_THROW(events.update(std::vector<Pair>{{6, 7}, {1, 8}, {6, 7}}), ArgumentError);  // new, twice
    EXPECT_THROW(events.update(std::vector<Pair>{{4, 5}, {1, 8}, {4, 5}}), ArgumentError);  // kept, twice
    EXPECT_THROW(events.update(std::vector<Pair>{{1, 2}, {1, 2}}), ArgumentError);          // replaced, twice
    EXPECT_THROW(events.swap_remove(3, 2), ArgumentError);
    EXPECT_EQ(as_vector(events.begun()), begun);
    EXPECT_EQ(as_vector(events.ended()), ended);
    EXPECT_EQ(events.size(), 2U);
    // The replace() before the failures still holds.
    events.update(std::vector<Pair>{{1, 2}, {4, 5}});
    EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{1, 2}}));
    EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{1, 2}}));
}

TEST(PairEvents, ClearAndMoveStartAfresh) {
    PairEvents events;
    events.update(std::vector<Pair>{{1, 2}});
    EXPECT_GT(events.bytes_held(), 0U);
    PairEvents moved(std::move(events));
    EXPECT_EQ(moved.size(), 1U);
    EXPECT_EQ(events.size(), 0U);  // NOLINT(bugprone-use-after-move): moved-from is valid and empty
    EXPECT_TRUE(events.begun().empty());
    events.update(std::vector<Pair>{{1, 2}});
    EXPECT_EQ(events.begun().size(), 1U);
    moved.clear();
    moved.update(std::vector<Pair>{{1, 2}});
    EXPECT_EQ(as_vector(moved.begun()), (std::vector<Pair>{{1, 2}}));
    EXPECT_TRUE(moved.ended().empty());
}

}  // namespace
}  // namespace smb::test
