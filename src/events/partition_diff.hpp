// SPDX-License-Identifier: MIT
#pragma once
// One partition of the previous pair list against the same partition of the current one: the
// previous pairs go into a small open-addressing table, the current ones probe it. A current
// pair not found is a candidate to begin (it may be a renamed previous pair, which lives
// elsewhere: pair_events.cpp settles those); a previous pair not found has ended.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "events/body_fates.hpp"
#include "events/pair_partitions.hpp"
#include "smb/errors.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// A previous pair under a new name: `now` is to be looked for among the candidates, `before`
/// is reported if it ended.
struct RenamedPair {
    Pair now;
    Pair before;
};

/// What the partitions found, and the tables they reuse.
struct DiffScratch {
    /// Slots of the partition's table: the previous pair at index i as table_base + i + 1, so
    /// that every slot at most table_base, left by the partitions before, reads as empty and
    /// the table is not cleared between partitions.
    std::vector<std::uint32_t> table;
    std::uint32_t table_base = 0;
    std::vector<std::uint8_t> matched;
    std::vector<Pair> candidates;
    std::vector<Pair> ended;
    std::vector<RenamedPair> renamed;
    /// A unit's pairs where they do not lie back to back (PairPartitions::unit()).
    std::vector<PackedPair> previous_unit;
    std::vector<PackedPair> current_unit;

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return table.capacity() * sizeof(std::uint32_t) + matched.capacity() +
               (candidates.capacity() + ended.capacity()) * sizeof(Pair) + renamed.capacity() * sizeof(RenamedPair) +
               (previous_unit.capacity() + current_unit.capacity()) * sizeof(PackedPair);
    }
};

[[noreturn]] inline void throw_repeated_pair(const Pair& pair) {
    throw ArgumentError("PairEvents::update: pair (" + std::to_string(pair.a) + ", " + std::to_string(pair.b) +
                        ") is listed twice");
}

/// Compares `previous` with `current`, both the pairs of one partition of `unit_bits` hash
/// bits, each in either form (pair_partitions.hpp). `fates` is null when no body changed name
/// since the previous list.
template <class PreviousPair, class CurrentPair>
void diff_partition(std::span<const PreviousPair> previous, std::span<const CurrentPair> current, int unit_bits,
                    const BodyFates* fates, DiffScratch& scratch) {
    if (previous.empty()) {
        for (const CurrentPair& pair : current) scratch.candidates.push_back(unpacked(pair));
        return;
    }
    // 32 slots a pair (128 KiB for a partition of a thousand, in L2; never cleared): nearly every
    // probe ends at its first slot. Measured at 1M boxes (3D, update factor 1e-3, 2-core Xeon
    // VM), the whole update took 29.6-30.4 ms with four slots a pair, 27.3-28.3 with eight,
    // 26.5-27.5 with 16, 26.2-26.5 with 32 and 27.5-28.7 with 64.
    int table_bits = 3;
    while ((std::size_t{1} << table_bits) < 32 * previous.size()) ++table_bits;
    const std::size_t mask = (std::size_t{1} << table_bits) - 1;
    // The partition took the top unit_bits bits of the hash; the table takes the next ones.
    const auto slot_of = [&](const auto& pair) {
        return static_cast<std::size_t>((pair_hash(pair) << unit_bits) >> (64 - table_bits));
    };
    auto& table = scratch.table;
    auto& matched = scratch.matched;
    if (table.size() < mask + 1) table.resize(mask + 1, 0);
    if (scratch.table_base > UINT32_MAX - previous.size() - 1) {
        std::fill(table.begin(), table.end(), 0);
        scratch.table_base = 0;
    }
    const std::uint32_t base = scratch.table_base;
    scratch.table_base += static_cast<std::uint32_t>(previous.size());
    matched.assign(previous.size(), 0);

    // The lists come from memory, a partition at a time: reading 32 pairs ahead took the diff
    // from 13.3 to 12.5 ms at 1M boxes.
    constexpr std::size_t kAhead = 32;
    for (std::size_t i = 0; i < previous.size(); ++i) {
        if (i + kAhead < previous.size()) __builtin_prefetch(&previous[i + kAhead]);
        std::size_t slot = slot_of(previous[i]);
        while (table[slot] > base) slot = (slot + 1) & mask;
        table[slot] = base + static_cast<std::uint32_t>(i + 1);
    }

    for (std::size_t j = 0; j < current.size(); ++j) {
        if (j + kAhead < current.size()) __builtin_prefetch(&current[j + kAhead]);
        const CurrentPair& pair = current[j];
        std::size_t slot = slot_of(pair);
        for (;;) {
            const std::uint32_t entry = table[slot];
            if (entry <= base) {
                scratch.candidates.push_back(unpacked(pair));
                break;
            }
            const std::size_t i = entry - base - 1;
            if (same_pair(previous[i], pair)) {
                if (matched[i] != 0) throw_repeated_pair(unpacked(pair));
                matched[i] = 1;
                break;
            }
            slot = (slot + 1) & mask;
        }
    }

    // A previous pair of a body with a fate is matched here only by a pair of the same names
    // that pair_events.cpp finds again among the watched ones; one not matched has no pair of
    // its names now: it ended, or goes on renamed.
    for (std::size_t i = 0; i < previous.size(); ++i) {
        if (matched[i] != 0) continue;
        const Pair pair = unpacked(previous[i]);
        Pair now;
        if (fates != nullptr && fates->may_touch(pair) && fates->follow(pair, now) == BodyFates::Outcome::renamed) {
            scratch.renamed.push_back({now, pair});
        } else {
            scratch.ended.push_back(pair);
        }
    }
}

}  // namespace smb::detail
