// SPDX-License-Identifier: MIT
#pragma once
// What became of the bodies of the previous pair list, from the replace() and swap_remove()
// calls made since: each previous body is gone, or under a new name, or (the default, which
// holds no memory) where it was. The calls are recorded as they come (a push, so a call that
// throws changes nothing) and replayed here when the next update needs them.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "smb/pair.hpp"

namespace smb::detail {

/// One recorded call: replace(first) when `swap` is false, swap_remove(first, second) else.
struct BodyCall {
    BoxId first = 0;
    BoxId second = 0;
    bool swap = false;
};

class BodyFates {
public:
    /// What a previous pair became.
    enum class Outcome : std::uint8_t { same, renamed, ended };

    /// Replays `calls`, then `replaced` as replace() calls.
    BodyFates(std::span<const BodyCall> calls, std::span<const BoxId> replaced) {
        for (const BodyCall& call : calls) {
            if (call.swap)
                swap_remove(call.first, call.second);
            else
                replace(call.first);
        }
        for (const BoxId name : replaced) replace(name);
        build_filter();
    }

    [[nodiscard]] bool empty() const noexcept { return fate_.empty(); }

    /// Whether `pair` may name a body with a fate, by its previous names or by its names now (a
    /// name whose body is not the one named so before): a filter of one bit per name, so that
    /// the pairs of bodies left alone (nearly all) cost a load or two each. Exact where the
    /// names are below 2^27; a hashed filter lets through more.
    [[nodiscard]] bool may_touch(const Pair& pair) const noexcept { return marked(pair.a) || marked(pair.b); }

    /// What became of the previous pair `pair`; `renamed` gives its new name in `now`.
    [[nodiscard]] Outcome follow(const Pair& pair, Pair& now) const {
        const auto a = lookup(fate_, pair.a);
        const auto b = lookup(fate_, pair.b);
        if (!a || !b) return Outcome::ended;
        if (*a == pair.a && *b == pair.b) return Outcome::same;
        now = *a < *b ? Pair{*a, *b} : Pair{*b, *a};
        return Outcome::renamed;
    }

private:
    static constexpr int kFilterBits = 16;

    void replace(BoxId name) {
        if (const auto body = lookup(holder_, name)) fate_[*body] = std::nullopt;
        holder_[name] = std::nullopt;
    }
    void swap_remove(BoxId removed, BoxId last) {
        const auto gone = lookup(holder_, removed);
        const auto moved = lookup(holder_, last);
        if (gone) fate_[*gone] = std::nullopt;
        if (removed != last && moved) fate_[*moved] = removed;
        holder_[removed] = removed != last ? moved : std::nullopt;
        if (removed != last) holder_[last] = std::nullopt;
    }

    using Names = std::unordered_map<BoxId, std::optional<BoxId>>;
    /// What `names` holds for `name`; `name` itself where it holds nothing.
    [[nodiscard]] static std::optional<BoxId> lookup(const Names& names, BoxId name) {
        const auto it = names.find(name);
        return it != names.end() ? it->second : std::optional<BoxId>(name);
    }

    /// Exact, one bit per name up to the largest name marked, where that is below 2^27 (16 MiB;
    /// indices and dense ids); else one bit per hashed name. A hashed filter lets through a
    /// share of the pairs as large as its share of bits set, each costing two map lookups.
    void build_filter() {
        BoxId largest = 0;
        for (const auto& entry : fate_) largest = std::max(largest, entry.first);
        for (const auto& entry : holder_) largest = std::max(largest, entry.first);
        exact_ = largest < (BoxId{1} << 27);
        filter_.assign(exact_ ? static_cast<std::size_t>(largest / 64 + 1) : (std::size_t{1} << kFilterBits) / 64, 0);
        const auto mark = [&](BoxId name) {
            const std::size_t bit = filter_bit(name);
            filter_[bit / 64] |= std::uint64_t{1} << (bit % 64);
        };
        for (const auto& entry : fate_) mark(entry.first);
        for (const auto& entry : holder_) mark(entry.first);
    }
    [[nodiscard]] bool marked(BoxId name) const noexcept {
        if (exact_ && name >= filter_.size() * 64) return false;
        const std::size_t bit = filter_bit(name);
        return (filter_[bit / 64] >> (bit % 64) & 1) != 0;
    }
    [[nodiscard]] std::size_t filter_bit(BoxId name) const noexcept {
        if (exact_) return static_cast<std::size_t>(name);
        return static_cast<std::size_t>((name * 0x9E3779B97F4A7C15ULL) >> (64 - kFilterBits));
    }

    /// By previous body: its name now, none if it is gone (a body not here is where it was).
    Names fate_;
    /// By name: the previous body now there (one moved there) or none (a name not here holds the
    /// body named so before).
    Names holder_;
    std::vector<std::uint64_t> filter_;
    bool exact_ = true;
};

}  // namespace smb::detail
