// SPDX-License-Identifier: MIT
// The layout of a pair list by partition, on the paths ordinary lists seldom take: partitions
// crowded past their room (the pairs go to the spill), lists of very different sizes compared
// (a unit gathered from several partitions), a name of more than 32 bits met late in the list,
// and bad pairs met after the layout began. Every update against std::set_difference.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <random>
#include <set>
#include <span>
#include <vector>

#include "events/pair_partitions.hpp"
#include "reference/pair_sets.hpp"
#include "smb/pair_events.hpp"

namespace smb::test {
namespace {

/// `count` distinct pairs of names below `names`, of which `crowded` hash into the first
/// partition of a list of `count` pairs (the top partition bits all zero), in random order.
std::vector<Pair> crowded_pairs(std::mt19937_64& random, std::size_t count, std::size_t crowded, BoxId names) {
    const int bits = detail::partition_bits_for(count);
    std::set<Pair> in_first;
    std::set<Pair> elsewhere;
    std::uniform_int_distribution<BoxId> name(0, names - 1);
    while (in_first.size() + elsewhere.size() < count) {
        const BoxId a = name(random);
        const BoxId b = name(random);
        if (a == b) continue;
        const Pair pair{std::min(a, b), std::max(a, b)};
        const bool first = bits > 0 && (detail::pack_pair(pair.a, pair.b) >> (64 - bits)) == 0;
        if (first && in_first.size() < crowded) {
            in_first.insert(pair);
        } else if (!first && elsewhere.size() + crowded < count) {
            elsewhere.insert(pair);
        }
    }
    std::vector<Pair> pairs(in_first.begin(), in_first.end());
    pairs.insert(pairs.end(), elsewhere.begin(), elsewhere.end());
    std::shuffle(pairs.begin(), pairs.end(), random);
    return pairs;
}

void expect_events(const PairEvents& events, const std::vector<Pair>& previous, const std::vector<Pair>& next,
                   int round) {
    EXPECT_EQ(as_vector(events.begun()), difference(next, previous)) << round;
    EXPECT_EQ(as_vector(events.ended()), difference(previous, next)) << round;
    EXPECT_EQ(events.size(), next.size()) << round;
}

/// Updates `events` with a list per round (counts[r] pairs, crowded[r] of them in the first
/// partition, names below `names`), half of each list kept from the one before, checking the
/// events after every update.
void expect_rounds(PairEvents& events, std::mt19937_64& random, std::span<const std::size_t> counts,
                   std::span<const std::size_t> crowded, BoxId names) {
    std::vector<Pair> previous;
    for (std::size_t round = 0; round < counts.size(); ++round) {
        std::vector<Pair> next = crowded_pairs(random, counts[round], crowded[round], names);
        for (std::size_t i = 0; i < previous.size() && i < next.size(); i += 2) next[i] = previous[i];
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::shuffle(next.begin(), next.end(), random);
        events.update(next);
        expect_events(events, previous, next, static_cast<int>(round));
        previous = next;
    }
}

TEST(PairEventsLayout, CrowdedPartitionsSpill) {
    // 20 000 pairs lay out in 32 partitions of some 625; a third of them in the first one
    // overflows its room by thousands, from one update to the next and back.
    std::mt19937_64 random(53);
    PairEvents events;
    std::vector<Pair> previous;
    const std::size_t crowded[] = {7000, 200, 7000, 7000, 0, 19000};
    for (int round = 0; round < 6; ++round) {
        std::vector<Pair> next = crowded_pairs(random, 20000, crowded[round], 30000);
        // Keep part of the previous list, crowded or not.
        for (std::size_t i = 0; i < previous.size() && i < next.size(); i += 2) next[i] = previous[i];
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        std::shuffle(next.begin(), next.end(), random);
        events.update(next);
        expect_events(events, previous, next, round);
        previous = next;
    }
    // A spilled pair listed twice is refused, and changes nothing.
    std::vector<Pair> repeated = crowded_pairs(random, 20000, 9000, 30000);
    const auto begun = as_vector(events.begun());
    const int bits = detail::partition_bits_for(repeated.size());
    for (const Pair& pair : repeated) {
        if (detail::pack_pair(pair.a, pair.b) >> (64 - bits) == 0) {
            repeated.push_back(pair);
            break;
        }
    }
    EXPECT_THROW(events.update(repeated), ArgumentError);
    EXPECT_EQ(as_vector(events.begun()), begun);
    EXPECT_EQ(events.size(), previous.size());
    events.update(std::span<const Pair>(repeated.data(), repeated.size() - 1));
    expect_events(events, previous, {repeated.begin(), repeated.end() - 1}, 6);
}

TEST(PairEventsLayout, ListsOfVeryDifferentSizes) {
    // A list of one partition against one of many, both ways, crowded or not: each partition of
    // the finer layout is compared within its unit of the coarser one.
    std::mt19937_64 random(59);
    PairEvents events;
    const std::size_t counts[] = {300, 40000, 900, 40000, 2500, 70000, 10};
    const std::size_t crowded[] = {0, 15000, 0, 0, 2000, 30000, 0};
    expect_rounds(events, random, counts, crowded, 60000);
}

TEST(PairEventsLayout, WideNameOrBadPairLateInTheList) {
    // The one-pass layout packs as it goes: a name past 32 bits near the end makes it start
    // over, wide; a pair with a >= b near the end is refused with nothing changed.
    std::mt19937_64 random(61);
    PairEvents events;
    std::vector<Pair> previous = crowded_pairs(random, 30000, 8000, 40000);
    events.update(previous);
    std::vector<Pair> next = crowded_pairs(random, 30000, 8000, 40000);
    for (std::size_t i = 0; i < next.size() && i < previous.size(); i += 3) next[i] = previous[i];
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    std::shuffle(next.begin(), next.end(), random);
    next.push_back({7, BoxId{1} << 40});
    events.update(next);
    expect_events(events, previous, next, 0);
    previous = next;

    const auto begun = as_vector(events.begun());
    const auto ended = as_vector(events.ended());
    std::vector<Pair> bad = crowded_pairs(random, 30000, 8000, 40000);
    bad.push_back({9, 9});
    EXPECT_THROW(events.update(bad), ArgumentError);
    bad.back() = {12, 11};
    EXPECT_THROW(events.update(bad), ArgumentError);
    EXPECT_EQ(as_vector(events.begun()), begun);
    EXPECT_EQ(as_vector(events.ended()), ended);
    EXPECT_EQ(events.size(), previous.size());
    bad.pop_back();
    events.update(bad);
    expect_events(events, previous, bad, 1);
}

TEST(PairEventsLayout, OnePassAndCountedLayoutsCompared) {
    // On two threads a list of fewer than 2^17 pairs is laid out in one pass, a longer one by
    // counting; the layouts of two updates may differ either way, crowded or not.
    std::mt19937_64 random(67);
    PairEvents events(2);
    const std::size_t counts[] = {100000, 150000, 90000, 40000, 140000};
    const std::size_t crowded[] = {20000, 0, 0, 9000, 30000};
    expect_rounds(events, random, counts, crowded, 200000);
}

}  // namespace
}  // namespace smb::test
