// SPDX-License-Identifier: MIT
// Pair events under swap-removes, where a name is met again by other bodies: the fates of the
// previous bodies (src/events/body_fates.hpp) against a plain replay of the calls, with the
// exact filter (small names) and the hashed one (names past 2^27, many names sharing a bit
// with a marked one); a pair of the previous list and one of the new list under the same names
// but of other bodies; PairEvents on random lists with many swap-removes against the set
// differences of the lists named by body, packed and wide names, one and two threads.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "events/body_fates.hpp"
#include "reference/pair_sets.hpp"
#include "smb/pair_events.hpp"

namespace smb::test {
namespace {

/// The calls replayed on a map from name to body: the body under each name now.
struct ArrayModel {
    std::map<BoxId, std::int64_t> body_at;  // absent: the body named so before; -1: none (new)

    [[nodiscard]] std::int64_t body(BoxId name) const {
        const auto it = body_at.find(name);
        return it != body_at.end() ? it->second : static_cast<std::int64_t>(name);
    }
    void swap_remove(BoxId removed, BoxId last) {
        body_at[removed] = removed != last ? body(last) : -1;
        if (removed != last) body_at[last] = -1;
    }
    void replace(BoxId name) { body_at[name] = -1; }
    /// The name now of previous body `body`, none if gone.
    [[nodiscard]] std::optional<BoxId> name_of(BoxId previous) const {
        for (const auto& [name, now] : body_at) {
            if (now == static_cast<std::int64_t>(previous)) return name;
        }
        if (body_at.count(previous) != 0) return std::nullopt;  // its name holds another, it is gone
        return previous;
    }
};

void fates_against_model(BoxId offset) {
    std::mt19937_64 random(offset + 11);
    constexpr BoxId kNames = 4000;
    std::uniform_int_distribution<BoxId> any(0, kNames - 1);
    std::vector<detail::BodyCall> calls;
    ArrayModel model;
    BoxId last = offset + kNames - 1;
    for (int k = 0; k < 60; ++k) {
        const BoxId removed = offset + any(random) % (last - offset + 1);
        calls.push_back({removed, last, true});
        model.swap_remove(removed, last);
        --last;
        if (k % 7 == 0) {
            const BoxId name = offset + any(random) % (last - offset + 1);
            calls.push_back({name, 0, false});
            model.replace(name);
        }
    }
    const detail::BodyFates fates(calls, {});
    ASSERT_FALSE(fates.empty());
    std::size_t let_through = 0;  // pairs of bodies left alone that the filter let through
    // Pairs in the array, and pairs with random names past it: runs of names hash to
    // well-spread bits, random ones collide.
    std::vector<Pair> pairs;
    for (BoxId a = offset; a < offset + kNames; a += 3) {
        for (BoxId b = a + 1; b < offset + kNames; b += 97) pairs.push_back({a, b});
    }
    std::uniform_int_distribution<BoxId> far(offset + kNames, offset + (BoxId{1} << 32));
    for (int k = 0; k < 40000; ++k) pairs.push_back({offset + any(random), far(random)});
    for (const Pair& pair : pairs) {
        const BoxId a = pair.a;
        const BoxId b = pair.b;
        const auto na = model.name_of(a);
        const auto nb = model.name_of(b);
        const bool touched = na != a || nb != b;
        Pair now{};
        const auto outcome = fates.may_touch(pair) ? fates.follow(pair, now) : detail::BodyFates::Outcome::same;
        if (fates.may_touch(pair) && !touched) ++let_through;
        if (!na || !nb) {
            EXPECT_EQ(outcome, detail::BodyFates::Outcome::ended) << a << " " << b;
        } else if (!touched) {
            EXPECT_EQ(outcome, detail::BodyFates::Outcome::same) << a << " " << b;
        } else {
            ASSERT_EQ(outcome, detail::BodyFates::Outcome::renamed) << a << " " << b;
            EXPECT_EQ(now, (Pair{std::min(*na, *nb), std::max(*na, *nb)})) << a << " " << b;
        }
    }
    // Past 2^27 the filter is hashed: it lets some through, and follow() keeps them.
    if (offset >= (BoxId{1} << 27)) {
        EXPECT_GT(let_through, 0U);
    }
}

TEST(PairEventsRenaming, SameNamesOtherBodies) {
    for (const BoxId o : {BoxId{0}, BoxId{1} << 40}) {
        // A B C D at 0..3: A-B and A-D. swap_remove(1, 3) puts D at 1: A-D goes on as (0, 1),
        // A-B ends as (0, 1).
        PairEvents events;
        events.update(std::vector<Pair>{{o, o + 1}, {o, o + 3}, {o + 2, o + 3}});
        events.swap_remove(o + 1, o + 3);
        events.update(std::vector<Pair>{{o, o + 1}});
        EXPECT_TRUE(events.begun().empty()) << o;
        EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{o, o + 1}, {o + 2, o + 3}})) << o;
        // A D C at 0..2, E appended at 3: A-D, C-E. swap_remove(1, 3) puts E at 1; A-E is new
        // under A-D's names, C-E goes on as (1, 2).
        events.update(std::vector<Pair>{{o, o + 1}, {o + 2, o + 3}});
        events.swap_remove(o + 1, o + 3);
        events.update(std::vector<Pair>{{o, o + 1}, {o + 1, o + 2}});
        EXPECT_EQ(as_vector(events.begun()), (std::vector<Pair>{{o, o + 1}})) << o;
        EXPECT_EQ(as_vector(events.ended()), (std::vector<Pair>{{o, o + 1}})) << o;
    }
}

TEST(BodyFates, SmallNamesAgainstAModel) { fates_against_model(0); }
TEST(BodyFates, LargeNamesAgainstAModel) { fates_against_model(BoxId{1} << 40); }

/// `steps` random lists of `pair_count` pairs over an array of bodies kept by swap-remove, half of the
/// previous pairs going on; the events against the set differences of the lists named by body.
void swap_removes_against_set_difference(BoxId offset, unsigned threads, std::size_t pair_count, int steps) {
    std::mt19937_64 random(offset + 5);
    std::vector<std::uint64_t> bodies;  // the body at each index
    std::uint64_t next_body = 0;
    for (int i = 0; i < 3000; ++i) bodies.push_back(next_body++);
    PairEvents events(threads);
    std::set<std::pair<std::uint64_t, std::uint64_t>> before;
    std::vector<std::uint64_t> bodies_before;
    for (int step = 0; step < steps; ++step) {
        for (int k = 0; step > 0 && k < 150; ++k) {
            const std::size_t removed = std::uniform_int_distribution<std::size_t>(0, bodies.size() - 1)(random);
            const std::size_t last = bodies.size() - 1;
            bodies[removed] = bodies[last];
            bodies.pop_back();
            events.swap_remove(offset + removed, offset + last);
            if (k % 5 == 0) bodies.push_back(next_body++);
        }
        std::uniform_int_distribution<std::size_t> index(0, bodies.size() - 1);
        std::set<Pair> list;
        while (list.size() < pair_count) {
            const std::size_t i = index(random);
            const std::size_t j = index(random);
            if (i != j) list.insert({offset + std::min(i, j), offset + std::max(i, j)});
        }
        // Half of the previous pairs of bodies still here go on, under their names now.
        std::map<std::uint64_t, BoxId> name_of;
        for (std::size_t i = 0; i < bodies.size(); ++i) name_of[bodies[i]] = offset + i;
        std::size_t k = 0;
        for (const auto& [x, y] : before) {
            if (k++ % 2 == 0 || name_of.count(x) == 0 || name_of.count(y) == 0) continue;
            const BoxId a = name_of[x];
            const BoxId b = name_of[y];
            list.insert({std::min(a, b), std::max(a, b)});
        }
        std::vector<Pair> pairs(list.begin(), list.end());
        std::shuffle(pairs.begin(), pairs.end(), random);
        events.update(pairs);
        std::set<std::pair<std::uint64_t, std::uint64_t>> now;
        const auto by_body = [&](const Pair& pair, const std::vector<std::uint64_t>& at) {
            const std::uint64_t x = at[pair.a - offset];
            const std::uint64_t y = at[pair.b - offset];
            return std::pair{std::min(x, y), std::max(x, y)};
        };
        for (const Pair& pair : pairs) now.insert(by_body(pair, bodies));
        std::set<std::pair<std::uint64_t, std::uint64_t>> begun;
        for (const Pair& pair : events.begun()) begun.insert(by_body(pair, bodies));
        std::set<std::pair<std::uint64_t, std::uint64_t>> expected_begun;
        std::set_difference(now.begin(), now.end(), before.begin(), before.end(),
                            std::inserter(expected_begun, expected_begun.end()));
        EXPECT_EQ(begun, expected_begun) << step;
        EXPECT_EQ(events.begun().size(), expected_begun.size()) << step;
        std::set<std::pair<std::uint64_t, std::uint64_t>> expected_ended;
        std::set_difference(before.begin(), before.end(), now.begin(), now.end(),
                            std::inserter(expected_ended, expected_ended.end()));
        std::set<std::pair<std::uint64_t, std::uint64_t>> ended;
        for (const Pair& pair : events.ended()) ended.insert(by_body(pair, bodies_before));
        EXPECT_EQ(ended, expected_ended) << step;
        EXPECT_EQ(events.ended().size(), expected_ended.size()) << step;
        before = now;
        bodies_before = bodies;
    }
}

TEST(PairEventsRenaming, PackedNamesAgainstSetDifference) { swap_removes_against_set_difference(0, 1, 12000, 6); }
TEST(PairEventsRenaming, WideNamesAgainstSetDifference) {
    swap_removes_against_set_difference(BoxId{1} << 40, 1, 12000, 6);
}
TEST(PairEventsRenaming, TwoThreadsAgainstSetDifference) {
    // Enough pairs for the layout counted on two threads and a comparison on two.
    swap_removes_against_set_difference(0, 2, 140000, 2);
    swap_removes_against_set_difference(BoxId{1} << 40, 2, 140000, 2);
}

}  // namespace
}  // namespace smb::test
