// SPDX-License-Identifier: MIT
#pragma once
// Moving-against-static pairs through a cache per moving box, like a Verlet skin: each moving
// box keeps a fat box (itself grown by a skin) and a contiguous copy of the statics that
// overlap the fat box and whose filter bits pass with its own. While a box stays inside its fat
// box, a step tests it against its copies alone (sequential memory, no grid); a box that left
// it, or whose filter or statics changed, asks the grid (static_grid.hpp) again. The copies live
// in one pool, each box's in a range with some room: a fresh query that fits is written over
// the box's old range, one that does not gets a new range at the end of the pool (fresh memory
// and page faults were a third of the refreshes' cost), and the pool is closed up when half of
// it is dead. A copy is the static's lattice box (quantized_bounds.hpp) and its id beside it (a
// hit reads the line the test just read): 20 bytes a static (3D), against 32 with float boxes;
// reading them is most of what a step of this part costs.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/pair_output.hpp"
#include "filters/filtered_report.hpp"
#include "filters/quantized_bounds.hpp"
#include "filters/static_grid.hpp"
#include "smb/box.hpp"
#include "smb/filter.hpp"
#include "smb/pair.hpp"

namespace smb::detail {

template <std::floating_point Real, int Dim>
class StaticContacts {
public:
    /// Moving boxes that asked the grid again in the last detection.
    [[nodiscard]] std::size_t refreshed() const noexcept { return refreshed_; }
    /// Static copies the moving boxes held in the last detection, counted there (a pass of its
    /// own over the entries read them from memory once more, 6% of this part's time).
    [[nodiscard]] std::size_t cached() const noexcept { return cached_; }

    void clear() { *this = StaticContacts(); }

    /// The statics were indexed again: `moving` boxes, each of which asks the grid at the next
    /// detection. Until then (a world without statics) the calls below keep nothing, so that
    /// filters alone cost no entry per box.
    void track(std::size_t moving) {
        clear();
        entries_.assign(moving, Entry{});
        tracking_ = true;
    }
    void invalidate(std::size_t i) {
        if (tracking_) entries_[i].valid = false;
    }
    /// A new moving box at the end; it asks the grid at the next detection.
    void push_back() {
        if (tracking_) entries_.push_back(Entry{});
    }
    /// The moving boxes were swap-removed at i: the last now sits there.
    void swap_remove(std::size_t i) {
        if (!tracking_) return;
        dead_ += entries_[i].room;
        entries_[i] = entries_.back();
        entries_.pop_back();
    }

    /// Reports every pair of moving box i (boxes[i], with info[i]'s id and filter) and a static
    /// that overlap, whose bits pass and that pass `rules`.
    void detect(std::span<const Box<Real, Dim>> boxes, std::span<const IdFilter> info,
                const StaticGrid<Real, Dim>& grid, const PairRules& rules, PairOutput& output) {
        refreshed_ = 0;
        cached_ = 0;
        if (grid.empty()) return;
        if (dead_ > 4096 && 2 * dead_ > copies_.size()) close_up();
        const double skin_floor = 0.125 * grid.smallest_cell_side();
        for (std::size_t i = 0; i < boxes.size(); ++i) {
            if (i + kAhead < boxes.size()) prefetch_range(entries_[i + kAhead]);
            const Box<Real, Dim>& box = boxes[i];
            Entry& e = entries_[i];
            if (!e.valid || !inside(box, e.fat)) refresh(e, box, info[i].filter, grid, skin_floor);
            if (hits_.size() < e.count) hits_.resize(e.count);
            cached_ += e.count;
            // The hits first, without a branch per static (a quarter of them hit: a branch
            // would be mispredicted often); then their report, in order.
            const Lattice<Dim> lattice(e.fat, e.scale);
            const QuantOverlap<Dim> test(lattice.query(box));
            const Copy* first = copies_.data() + e.offset;
            std::uint32_t found = 0;
            for (std::uint32_t c = 0; c < e.count; ++c) {
                const unsigned result = test.test(first + c);  // 0: miss, 3: hit, 1: cannot tell
                hits_[found] = c;
                found += result >> 1;
                if (result == 1) [[unlikely]] {
                    if (overlaps(grid.box(indices_[e.offset + c]), box)) hits_[found++] = c;
                }
            }
            const BoxId a = info[i].id;
            for (std::uint32_t h = 0; h < found; ++h) {
                const BoxId b = first[hits_[h]].id();
                if (rules.pass(a, b)) output(a, b);
            }
        }
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return entries_.capacity() * sizeof(Entry) + copies_.capacity() * sizeof(Copy) +
               (indices_.capacity() + found_.capacity() + hits_.capacity()) * sizeof(std::uint32_t);
    }

private:
    /// A static's lattice box and its id, packed: the id as two 32-bit words, so that the copy is
    /// 20 bytes (3D) rather than 24, and the test's 16-byte read stays inside the copy.
    struct Copy {
        QuantBox<Dim> box;
        std::array<std::uint32_t, 2> id_words;

        Copy() = default;
        Copy(const QuantBox<Dim>& b, BoxId id) noexcept
            : box(b), id_words{static_cast<std::uint32_t>(id), static_cast<std::uint32_t>(id >> 32)} {}
        [[nodiscard]] BoxId id() const noexcept { return BoxId{id_words[0]} | (BoxId{id_words[1]} << 32); }
    };
    static_assert(sizeof(Copy) >= 16);

    struct Entry {
        FloatBox<Dim> fat{};  // outward: the grid was asked for the statics overlapping it
        std::array<float, Dim> scale{};
        std::size_t offset = 0;
        std::uint32_t count = 0;
        std::uint32_t room = 0;  // pool entries the range holds, count of them in use
        bool valid = false;
    };

    /// The skin: half the box's largest side, so that a box may travel about that far before it
    /// asks again; at least an eighth of a grid cell, for boxes of (almost) no size. On the
    /// paper's environment at Λ = 1e-3, a quarter made 4 times the refreshes (2.8% of the boxes
    /// a step after 20 steps, against 0.7%) for 0.55 times the copies; the refreshes cost more.
    void refresh(Entry& e, const Box<Real, Dim>& box, const Filter& filter, const StaticGrid<Real, Dim>& grid,
                 double skin_floor) {
        ++refreshed_;
        double largest = 0;
        for (int k = 0; k < Dim; ++k)
            largest = std::max(largest, static_cast<double>(box.max[k]) - static_cast<double>(box.min[k]));
        const auto skin = static_cast<Real>(std::max(0.5 * largest, skin_floor));
        Box<Real, Dim> fat;
        for (int k = 0; k < Dim; ++k) {
            // Rounding keeps the box inside: x - skin rounds to at most x, x + skin to at least x.
            fat.min[k] = box.min[k] - skin;
            fat.max[k] = box.max[k] + skin;
        }
        e.fat = outward_copy(fat);
        found_.clear();
        grid.query(widened<Real>(e.fat), [&](std::uint32_t s) {
            if (filters_pass(filter, grid.filter(s))) found_.push_back(s);
        });
        if (found_.size() > e.room) {
            dead_ += e.room;
            e.offset = copies_.size();
            e.room = static_cast<std::uint32_t>(found_.size() + found_.size() / 4 + 2);
            copies_.resize(copies_.size() + e.room);
            indices_.resize(indices_.size() + e.room);
        }
        e.scale = Lattice<Dim>::scales(e.fat);
        const Lattice<Dim> lattice(e.fat, e.scale);
        for (std::size_t j = 0; j < found_.size(); ++j) {
            const std::uint32_t s = found_[j];
            copies_[e.offset + j] = Copy(lattice.copy(grid.box(s)), grid.id(s));
            indices_[e.offset + j] = s;
        }
        e.count = static_cast<std::uint32_t>(found_.size());
        e.valid = true;
    }

    /// Boxes ahead whose copies are asked for before their test. The reading of the copies
    /// stalled on memory although the ranges mostly follow each other (on the paper's
    /// environment, 100k moving boxes among 1M statics: 10.9 ms a step for this part without,
    /// 8.5 to 9.0 with, two to eight boxes ahead alike).
    static constexpr std::size_t kAhead = 4;

    void prefetch_range(const Entry& e) const noexcept {
        // From the line the first copy starts in, so that the range's last line is asked for too.
        const auto to = reinterpret_cast<std::uintptr_t>(copies_.data() + e.offset + e.count);
        for (auto p = reinterpret_cast<std::uintptr_t>(copies_.data() + e.offset) & ~std::uintptr_t{63}; p < to;
             p += 64)
            __builtin_prefetch(reinterpret_cast<const void*>(p));
    }

    /// Copies the live ranges into a fresh pool in the boxes' order.
    void close_up() {
        const std::size_t live = copies_.size() - dead_ + copies_.size() / 8;
        std::vector<Copy> copies;
        std::vector<std::uint32_t> indices;
        copies.reserve(live);
        indices.reserve(live);
        for (Entry& e : entries_) {
            const auto from = static_cast<std::ptrdiff_t>(e.offset);
            const auto to = static_cast<std::ptrdiff_t>(e.offset + e.room);
            e.offset = copies.size();
            copies.insert(copies.end(), copies_.begin() + from, copies_.begin() + to);
            indices.insert(indices.end(), indices_.begin() + from, indices_.begin() + to);
        }
        copies_.swap(copies);
        indices_.swap(indices);
        dead_ = 0;
    }

    std::vector<Entry> entries_;
    // The pool, two arrays alike: the copies, and the statics' indices in the grid.
    std::vector<Copy> copies_;
    std::vector<std::uint32_t> indices_;
    std::vector<std::uint32_t> found_;  // one query's statics, before they go to the pool
    std::vector<std::uint32_t> hits_;   // one box's hits, as positions in its range
    std::size_t dead_ = 0;              // pool entries no box points to
    std::size_t refreshed_ = 0;
    std::size_t cached_ = 0;
    bool tracking_ = false;
};

}  // namespace smb::detail
