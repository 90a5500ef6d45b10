// SPDX-License-Identifier: MIT
#pragma once
// Where a cell check lays out its boxes and writes down its hits: one buffer, the columns of
// the cell at a stride that follows the cell's own size, and the hit list right after them.
//
// Why one buffer and not a vector per column: the pair test stores its hits while it loads the
// columns, and a store and a later load whose addresses agree in their low twelve bits are
// taken for the same place until the store's address is known (4K aliasing). With the columns
// and the hits placed by the heap, the check's speed depended on that placement, as one
// allocation size or another moved the hit list. Laid out back to back from a 4 KiB boundary,
// with the hits after every column, the hits of a cell of up to 80 boxes can fill 1 KiB before
// they share their place modulo 4 KiB with a column the pair test loads; the cells hold about 46
// boxes and pass about 38 pairs.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

namespace smb::detail {

template <int Dim>
class CellScratch {
public:
    using Mask = std::int32_t;

    /// The arrays of one cell, valid until the next lay_out_for().
    struct Columns {
        Mask* inside = nullptr;  // the cell's lower-corner bits, one per box
        std::array<float*, Dim> min{};
        std::array<float*, Dim> max{};
        std::uint32_t* position = nullptr;  // where the box lies in the ordered array
        std::uint32_t* key = nullptr;       // its x key (the sweep only)
        std::uint32_t* hits = nullptr;      // room for `hit_room` packed pairs
    };

    /// Arrays for `rows` boxes (padding included) and `hit_room` hits. Grows the buffer when it
    /// must, and never shrinks it.
    Columns lay_out_for(std::size_t rows, std::size_t hit_room) {
        const std::size_t stride = (rows + kFloatsPerLine - 1) / kFloatsPerLine * kFloatsPerLine;
        const std::size_t words = kColumns * stride + hit_room;
        if (words > capacity_) {
            capacity_ = std::max(words, capacity_ + capacity_ / 2);
            buffer_.reset(static_cast<std::uint32_t*>(::operator new(capacity_ * sizeof(std::uint32_t), kAlignment)));
        }
        // Implicitly created arrays of floats and integers in the allocated storage (C++20).
        std::byte* base = reinterpret_cast<std::byte*>(buffer_.get());
        auto column = [&](std::size_t index) { return base + index * stride * sizeof(std::uint32_t); };
        // First what the pair test's rows do not load: a hit list long enough to wrap round
        // 4 KiB meets these before it meets the columns the rows load.
        Columns columns;
        columns.position = reinterpret_cast<std::uint32_t*>(column(0));
        columns.key = reinterpret_cast<std::uint32_t*>(column(1));
        columns.inside = reinterpret_cast<Mask*>(column(2));
        for (int k = 0; k < Dim; ++k) {
            columns.min[k] = reinterpret_cast<float*>(column(3 + 2 * static_cast<std::size_t>(k)));
            columns.max[k] = reinterpret_cast<float*>(column(4 + 2 * static_cast<std::size_t>(k)));
        }
        columns.hits = reinterpret_cast<std::uint32_t*>(column(kColumns));
        return columns;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept { return capacity_ * sizeof(std::uint32_t); }

private:
    static constexpr std::size_t kColumns = 3 + 2 * Dim;  // position, key, inside, min and max per axis
    static constexpr std::size_t kFloatsPerLine = 16;     // a column starts on a cache line
    static constexpr std::align_val_t kAlignment{4096};   // the layout counts from a 4 KiB boundary

    struct Release {
        void operator()(std::uint32_t* words) const noexcept { ::operator delete(words, kAlignment); }
    };
    std::unique_ptr<std::uint32_t, Release> buffer_;
    std::size_t capacity_ = 0;  // in 4-byte words
};

}  // namespace smb::detail
