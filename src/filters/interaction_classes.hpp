// SPDX-License-Identifier: MIT
#pragma once
// The moving boxes of a World split by what their filter bits let them meet: two filter values
// are linked when their bits pass, and an interaction class is a set of values linked to each
// other, directly or through others. No box of one class can pair with a box of another, so
// each class is detected on its own (class_detections.hpp), and a class whose values pass with
// none of its own (a set whose mask meets no category of the scene) is not detected at all: two
// layers that ignore each other cost their two detections, not the one detection of all their
// boxes in which the pairs across the layers are found and dropped.
//
// The classes depend on the distinct filter values only, of which a scene has few (a layer, a
// set of a join, debris). Values are kept in a small table; a value not in it makes the classes
// stale, and they are built again from the moving boxes' filters before the next detection. A
// value that leaves the scene is kept until then: a class built with a value too many may join
// classes that could stay apart, which costs speed, never a pair. Past kMaxValues distinct
// values, every box is one class (the single detection of the filtered path).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "smb/filter.hpp"

namespace smb::detail {

class InteractionClasses {
public:
    static constexpr std::size_t kMaxValues = 64;
    static constexpr std::uint8_t kUnknown = 0xFE;  // never a class: there are at most kMaxValues

    /// Classes of the filter values of the boxes: filter_of(i) for i in [0, n). A value whose
    /// category or mask is 0 pairs with nothing and belongs to no class.
    template <class FilterOf>
    void build(std::size_t n, FilterOf&& filter_of) {
        clear();
        slots_.assign(kSlots, Slot{});
        for (std::size_t i = 0; i < n && !overflowed_; ++i) {
            const Filter f = filter_of(i);
            if (!filter_interacts(f) || find(f) != kMissing) continue;
            if (values_.size() == kMaxValues) {
                overflowed_ = true;
                break;
            }
            insert(f, static_cast<std::uint8_t>(values_.size()));
            values_.push_back(f);
        }
        if (overflowed_) {
            clear();
            overflowed_ = true;
            count_ = n == 0 ? 0 : 1;
            pairs_within_.assign(count_, true);
            return;
        }
        // Union-find over the values, then classes numbered in the order of their first value. A
        // value that passes with itself or a later one lets its class pair within: the later one
        // is linked to it, so of its class.
        std::vector<std::size_t> root(values_.size());
        std::iota(root.begin(), root.end(), std::size_t{0});
        const auto find_root = [&](std::size_t v) {
            while (root[v] != v) v = root[v] = root[root[v]];
            return v;
        };
        std::vector<bool> passes(values_.size(), false);
        for (std::size_t i = 0; i < values_.size(); ++i) {
            for (std::size_t j = i; j < values_.size(); ++j) {
                if (!filters_pass(values_[i], values_[j])) continue;
                root[find_root(i)] = find_root(j);
                passes[i] = true;
            }
        }
        std::vector<std::uint8_t> class_of_root(values_.size(), kMissing);
        value_class_.resize(values_.size());
        for (std::size_t v = 0; v < values_.size(); ++v) {
            std::uint8_t& c = class_of_root[find_root(v)];
            if (c == kMissing) {
                c = static_cast<std::uint8_t>(count_++);
                pairs_within_.push_back(false);
            }
            value_class_[v] = c;
            if (passes[v]) pairs_within_[c] = true;
        }
    }

    /// Forgets every value and gives the table back.
    void clear() {
        std::vector<Slot>().swap(slots_);
        values_.clear();
        value_class_.clear();
        pairs_within_.clear();
        count_ = 0;
        overflowed_ = false;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return slots_.capacity() * sizeof(Slot) + values_.capacity() * sizeof(Filter) + value_class_.capacity() +
               pairs_within_.capacity() / 8;
    }

    /// Classes (0 with no values; 1 after an overflow).
    [[nodiscard]] std::size_t count() const noexcept { return count_; }
    /// Whether there were more than kMaxValues values: one class.
    [[nodiscard]] bool overflowed() const noexcept { return overflowed_; }
    /// Whether the classes know the value (after an overflow, every value is in the one class).
    [[nodiscard]] bool knows(const Filter& f) const noexcept { return overflowed_ || find(f) != kMissing; }
    /// The class of a value, or kUnknown where the classes do not know it.
    [[nodiscard]] std::uint8_t class_of(const Filter& f) const noexcept {
        if (overflowed_) return 0;
        const std::uint8_t value = find(f);
        return value == kMissing ? kUnknown : value_class_[value];
    }
    /// Whether two boxes of class c may pair (some two of its values pass, one with itself
    /// included).
    [[nodiscard]] bool pairs_within(std::size_t c) const noexcept { return pairs_within_[c]; }

private:
    static constexpr std::uint8_t kMissing = 0xFF;
    static constexpr std::size_t kSlots = 4 * kMaxValues;  // a power of two

    /// A value of the table; key 0 is an empty slot (a value's category is never 0).
    struct Slot {
        std::uint64_t key = 0;
        std::uint8_t value = kMissing;
    };

    [[nodiscard]] static std::uint64_t key_of(const Filter& f) noexcept {
        return std::uint64_t{f.category} << 32 | f.mask;
    }
    [[nodiscard]] static std::size_t slot_of(std::uint64_t key) noexcept {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 56) & (kSlots - 1);
    }
    [[nodiscard]] std::uint8_t find(const Filter& f) const noexcept {
        if (slots_.empty()) return kMissing;
        const std::uint64_t key = key_of(f);
        for (std::size_t s = slot_of(key);; s = (s + 1) & (kSlots - 1)) {
            if (slots_[s].key == key) return slots_[s].value;
            if (slots_[s].key == 0) return kMissing;
        }
    }
    void insert(const Filter& f, std::uint8_t value) {
        const std::uint64_t key = key_of(f);
        std::size_t s = slot_of(key);
        while (slots_[s].key != 0) s = (s + 1) & (kSlots - 1);
        slots_[s] = Slot{key, value};
    }

    std::vector<Slot> slots_;  // kSlots once built: held only where the filtered path runs
    std::vector<Filter> values_;
    std::vector<std::uint8_t> value_class_;
    std::vector<bool> pairs_within_;
    std::size_t count_ = 0;
    bool overflowed_ = false;
};

}  // namespace smb::detail
