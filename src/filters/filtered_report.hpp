// SPDX-License-Identifier: MIT
#pragma once
// The reports a pipeline calls when it runs over a gathered array of boxes (index i of the array
// is one box): they test the filter bits, the static flags and the predicate of each pair, and hand the pairs
// that pass, under their ids, to the caller's output. The pipeline's own runs of pairs lose
// their (a < b) order through the ids, so they are reported one by one.
//
// The pipeline carries a 64-bit key per box in its cell order, and reports pairs of keys: where
// every id fits in 32 bits and every category in 16 (Box2D's width; then only the low 16 bits
// of a mask matter), the key is the id and the filter itself (PackedFilterReport), so that a
// pair is tested and reported without reading memory, as the default detection reports its
// ids. Otherwise the key is the index, and the filter and the id are read from one array in
// index order (FilteredReport): two cache misses a pair, which the packed keys save.

#include <cstdint>
#include <span>

#include "core/pair_output.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

/// A box's id and filter side by side: one cache line visit per box of a pair.
struct IdFilter {
    BoxId id;
    Filter filter;
};

/// Whether a box's key can hold its id and filter (see above).
[[nodiscard]] constexpr bool packable(BoxId id, const Filter& f) noexcept {
    return id <= 0xFFFFFFFFu && f.category <= 0xFFFFu;
}

/// id | category << 32 | (mask & 0xFFFF) << 48.
[[nodiscard]] constexpr BoxId packed_key(BoxId id, const Filter& f) noexcept {
    return id | (BoxId{f.category} << 32) | (BoxId{f.mask & 0xFFFFu} << 48);
}

/// What a pair takes after the filter bits: the static flags (a Detector's, by the ids it
/// reports, which are its indices; empty for a World, whose statics stay out of its detection)
/// and the predicate, if not null.
struct PairRules {
    std::span<const std::uint8_t> statics;
    const PairPredicate* predicate = nullptr;

    [[nodiscard]] bool pass(BoxId a, BoxId b) const {
        if (!statics.empty() && statics[a] != 0 && statics[b] != 0) return false;
        if (predicate == nullptr) return true;
        const Pair pair = ordered_pair(a, b);
        return (*predicate)(pair.a, pair.b);
    }
};

template <class Output>
class PackedFilterReport {
public:
    PackedFilterReport(Output& output, const PairRules& rules) : output_(output), rules_(rules) {}

    [[gnu::always_inline]] inline void operator()(BoxId a, BoxId b) {
        const BoxId category_a = (a >> 32) & 0xFFFFu;
        const BoxId category_b = (b >> 32) & 0xFFFFu;
        if ((category_a & (b >> 48)) == 0 || (category_b & (a >> 48)) == 0) return;
        const BoxId id_a = a & 0xFFFFFFFFu;
        const BoxId id_b = b & 0xFFFFFFFFu;
        if (rules_.pass(id_a, id_b)) output_(id_a, id_b);
    }

    void append(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) (*this)(p.a, p.b);
    }

private:
    Output& output_;
    PairRules rules_;
};

template <class Output>
class FilteredReport {
public:
    FilteredReport(Output& output, std::span<const IdFilter> boxes, const PairRules& rules)
        : output_(output), boxes_(boxes), rules_(rules) {}

    void operator()(BoxId a, BoxId b) {
        const IdFilter& x = boxes_[a];
        const IdFilter& y = boxes_[b];
        if (filters_pass(x.filter, y.filter) && rules_.pass(x.id, y.id)) output_(x.id, y.id);
    }

    void append(std::span<const Pair> pairs) {
        for (const Pair& p : pairs) (*this)(p.a, p.b);
    }

private:
    Output& output_;
    std::span<const IdFilter> boxes_;
    PairRules rules_;
};

}  // namespace smb::detail
