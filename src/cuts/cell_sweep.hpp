#pragma once
// The cell check of the persistent-cut pipeline, in one of two ways by the number m of boxes
// registered in the cell. Either way the boxes are copied out one array per coordinate (as
// floats), so that the check reads small contiguous arrays, eight candidates at a time.
//
// - Up to kAllPairsLimit boxes (nearly every cell: the cuts aim at about 24 boxes a cell, about
//   46 registered in 3D): every pair is tested, in the order the boxes were registered. No keys,
//   no sort, and loops whose lengths do not depend on the boxes' sizes, which a sweep's scan
//   does, at one mispredicted exit per box. The hits are written down without a branch (a
//   compress through a permutation table) and reported after the rows.
// - Beyond (a crowd the cuts cannot split, or a large target population): the boxes get local
//   numbers (the global-local map of the paper), are sorted on x by DIS with one increment (the
//   list arrives almost sorted: it follows last step's order), and are swept on x with direct
//   tests on the other axes.
//
// A pair shared by several cells is reported only by the cell that holds the lower corner of the
// two boxes' intersection, p[k] = max(a.min[k], b.min[k]). This replaces the paper's mask array:
// it needs no per-box state, and it stays exact whatever the number of cells a box touches.
// Every box registered in a cell has min[k] < the cell's upper plane on every axis (its min lies
// in the cell's segment or before it), so p lies in the cell iff, on every axis, a.min[k] or
// b.min[k] is at or above the cell's lower plane: one bit per axis and box, computed once.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <type_traits>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/assert.hpp"
#include "core/id_index.hpp"
#include "cuts/cell_scratch.hpp"
#include "smb/box.hpp"
#include "smb/pair.hpp"

namespace smb::detail {


/// Lower planes of a cell on every axis (-inf where the cell is first on that axis).
template <std::floating_point Real, int Dim>
using CellFloor = std::array<Real, Dim>;

/// `value` as the nearest float; beyond the float range, the largest float of its sign (a
/// plain conversion would be undefined there). Rounding never reverses an order: x <= y gives
/// to_float(x) <= to_float(y), which is all the cell check asks of it.
template <std::floating_point Real>
[[nodiscard]] inline float to_float(Real value) noexcept {
    if constexpr (std::is_same_v<Real, float>) {
        return value;
    } else {
        constexpr auto top = static_cast<Real>(std::numeric_limits<float>::max());
        return static_cast<float>(std::clamp(value, -top, top));
    }
}

/// A 32-bit key that never decreases as `value` grows: `value` rounded down to float, with -0
/// made +0 (they are equal coordinates), mapped so that unsigned order is numeric order.
template <std::floating_point Real>
[[nodiscard]] inline std::uint32_t monotone_key(Real value) noexcept {
    const float rounded = to_float(value) + 0.0F;  // -0 + 0 = +0
    const auto bits = std::bit_cast<std::uint32_t>(rounded);
    std::uint32_t key = (bits & 0x80000000U) != 0 ? ~bits : bits | 0x80000000U;
    if constexpr (!std::is_same_v<Real, float>) {
        // Rounded up: the next key down is the next float down (never below -inf's key).
        key -= static_cast<Real>(rounded) > value ? 1U : 0U;
    }
    return key;
}

/// Lanes of the sweep: four floats fill an SSE (or NEON) register, eight an AVX2 one.
template <std::size_t Lanes>
struct SweepLanes;
template <>
struct SweepLanes<4> {
    using Floats [[gnu::vector_size(16)]] = float;
    using Masks [[gnu::vector_size(16)]] = std::int32_t;
};
template <>
struct SweepLanes<8> {
    using Floats [[gnu::vector_size(32)]] = float;
    using Masks [[gnu::vector_size(32)]] = std::int32_t;
};

// Eight lanes where the processor has AVX2 (chosen when the program runs: the library is built
// for the baseline x86-64), four elsewhere. GCC only: clang 14, which builds the fuzzers,
// takes the four lanes. The environment variable SMB_NO_AVX2 (any value) forces the four
// lanes, so that the tests and benchmarks can check and time them on an AVX2 machine.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SMB_SWEEP_AVX2 1
[[nodiscard]] inline bool cpu_has_avx2() noexcept {
    static const bool has = __builtin_cpu_supports("avx2") != 0 && std::getenv("SMB_NO_AVX2") == nullptr;
    return has;
}
#else
#define SMB_SWEEP_AVX2 0
#endif
#if SMB_SWEEP_AVX2
#include <immintrin.h>
#endif

/// One bit per lane whose mask is set (all ones): a single instruction on x86-64, where the
/// compiler would otherwise take the lanes out one by one.
template <std::size_t Lanes>
[[nodiscard]] inline unsigned lane_bits(const typename SweepLanes<Lanes>::Masks& hit) noexcept {
    unsigned bits = 0;
    for (std::size_t lane = 0; lane < Lanes; ++lane) bits |= static_cast<unsigned>(hit[lane] & 1) << lane;
    return bits;
}
#if defined(__x86_64__) && defined(__GNUC__)
template <>
[[nodiscard]] inline unsigned lane_bits<4>(const SweepLanes<4>::Masks& hit) noexcept {
    return static_cast<unsigned>(__builtin_ia32_movmskps(__builtin_bit_cast(SweepLanes<4>::Floats, hit)));
}
#endif
#if SMB_SWEEP_AVX2
template <>
[[gnu::target("avx2")]] [[nodiscard]] inline unsigned lane_bits<8>(const SweepLanes<8>::Masks& hit) noexcept {
    return static_cast<unsigned>(__builtin_ia32_movmskps256(__builtin_bit_cast(SweepLanes<8>::Floats, hit)));
}
#endif

/// Writes the values of the lanes set in `bits` to `out`, in lane order, and returns the end of
/// what it wrote; the Lanes slots from `out` on may all be written. No branch on the bits.
template <std::size_t Lanes>
[[gnu::always_inline]] inline std::uint32_t* append_set_lanes(std::uint32_t* out, unsigned bits,
                                                              const typename SweepLanes<Lanes>::Masks& values) noexcept {
    for (std::size_t lane = 0; lane < Lanes; ++lane) {
        *out = static_cast<std::uint32_t>(values[lane]);
        out += (bits >> lane) & 1U;
    }
    return out;
}
#if SMB_SWEEP_AVX2
/// For each byte of lane bits, the numbers of its set lanes, lowest first, a byte each: the
/// permutation that packs those lanes to the front of a register (vpermd).
inline constexpr std::array<std::uint64_t, 256> kSetLaneOrder = [] {
    std::array<std::uint64_t, 256> table{};
    for (unsigned bits = 0; bits < 256; ++bits) {
        unsigned filled = 0;
        for (unsigned lane = 0; lane < 8; ++lane) {
            if ((bits >> lane & 1U) != 0) table[bits] |= std::uint64_t{lane} << (8 * filled++);
        }
    }
    return table;
}();
template <>
[[gnu::target("avx2,popcnt")]] inline std::uint32_t* append_set_lanes<8>(std::uint32_t* out, unsigned bits,
                                                                         const SweepLanes<8>::Masks& values) noexcept {
    const __m256i order = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kSetLaneOrder[bits])));
    const __m256i packed = _mm256_permutevar8x32_epi32(__builtin_bit_cast(__m256i, values), order);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), packed);
    return out + std::popcount(bits);
}
#endif

template <std::floating_point Real, int Dim>
class CellSweep {
public:
    static constexpr std::uint32_t kAllInside = (1U << Dim) - 1;

    /// Cells of up to this many registered boxes are checked by testing every pair. Measured
    /// against the sweep at 1M boxes (docs/performance.md): the all-pairs test is faster at the
    /// cells' usual ~46 boxes (the check 94 -> 74 ms in 3D, 45 -> 38 ms in 2D) and still at ~130
    /// (a target population of 64); its cost grows as m^2 / 16 lane groups, so crowds are swept.
    static constexpr std::size_t kAllPairsLimit = 128;
    /// check_all_pairs() packs a pair of local numbers as i << 16 | j in the lanes' signed
    /// 32-bit integers: it takes cells of up to this many boxes (the pipeline's are at most
    /// kAllPairsLimit).
    static constexpr std::size_t kMostPaired = std::size_t{1} << 15;

    /// Reports every pair of `entries` (positions of the boxes registered in the cell) whose
    /// lower intersection corner lies in the cell, and appends to `home` the positions whose own
    /// lower corner does: the order the next detection starts from. Returns the insertion-sort
    /// moves (none when every pair is tested).
    template <class Report, class Id>
    std::size_t check(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                      std::span<const Id> ids, const CellFloor<Real, Dim>& floor, Report& report,
                      std::vector<std::uint32_t>& home) {
        if (entries.size() <= kAllPairsLimit) {
            check_all_pairs(entries, boxes, floor, report, home);
            return 0;
        }
        return check_by_sweep(entries, boxes, ids, floor, report, home);
    }

    /// Held boxes that overlap by at least `margin` on every axis (held_sure_margin()) hold
    /// input boxes that overlap: the all-pairs test then calls report(a, b, true) where the
    /// report takes a third argument, and report(a, b, false) for the other pairs it passes,
    /// which the caller tests again. The default, infinity, proves nothing.
    void set_sure_margin(float margin) noexcept { sure_margin_ = margin; }

    /// check() by testing every pair; `home` gets the positions in the order of `entries`.
    template <class Report>
    void check_all_pairs(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                         const CellFloor<Real, Dim>& floor, Report& report, std::vector<std::uint32_t>& home) {
        lay_out(entries, boxes, floor);
        test_all_pairs(entries.size(), boxes, report, home);
    }

    /// check() by a sort and a sweep on x; `home` gets the positions in x order (ties by
    /// coordinate and id). Returns the insertion-sort moves.
    template <class Report, class Id>
    std::size_t check_by_sweep(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                               std::span<const Id> ids, const CellFloor<Real, Dim>& floor, Report& report,
                               std::vector<std::uint32_t>& home) {
        const std::size_t m = entries.size();
        order_.resize(m);
        std::uint64_t* order = order_.data();
        for (std::size_t i = 0; i < m; ++i)
            order[i] = (std::uint64_t{monotone_key(boxes[entries[i]].min[0])} << 32) | i;
        const std::size_t moves = insertion_sort(order, m);
        order_equal_keys(order, m, entries, boxes, ids);
        lay_out_sorted(order, m, entries, boxes, floor);
        sweep(m, boxes, report);
        append_home(m, home);
        return moves;
    }

    [[nodiscard]] std::size_t bytes_held() const noexcept {
        return order_.capacity() * sizeof(std::uint64_t) + scratch_.bytes_held() +
               own_home_.capacity() * sizeof(std::uint32_t);
    }

private:
    // Four or eight candidates are tested at once (GCC vector extensions; SweepLanes), always on
    // floats. Double boxes are laid out rounded to floats (to_float), which keeps every order,
    // so the float test passes every pair that overlaps, and each pair it passes is tested
    // again exactly. Four double lanes fill two SSE registers and measured slower than one
    // candidate at a time (and the layout takes twice the bytes); four float lanes fill one.
    static constexpr std::size_t kPadding = 8;  // the most lanes

    static constexpr bool kExactLanes = std::is_same_v<Real, float>;
    using Mask = typename CellScratch<Dim>::Mask;

    void lay_out_sorted(const std::uint64_t* order, std::size_t m, std::span<const std::uint32_t> entries,
                        std::span<const Box<Real, Dim>> boxes, const CellFloor<Real, Dim>& floor) {
        lay_out_columns(m, 0, [&](std::size_t r) { return entries[order[r] & 0xFFFFFFFFU]; },
                        [&](std::size_t r) { return static_cast<std::uint32_t>(order[r] >> 32); }, boxes, floor);
    }

    /// As registered, for the all-pairs test, which reads no keys, with room for every pair.
    void lay_out(std::span<const std::uint32_t> entries, std::span<const Box<Real, Dim>> boxes,
                 const CellFloor<Real, Dim>& floor) {
        const std::size_t m = entries.size();
        lay_out_columns(m, m * (m - (m > 0 ? 1 : 0)) / 2 + kPadding, [&](std::size_t r) { return entries[r]; },
                        NoKeys{}, boxes, floor);
    }

    struct NoKeys {};  // the all-pairs test reads no keys: none are written

    template <class PositionAt, class KeyAt>
    [[gnu::always_inline]] inline void lay_out_columns(std::size_t m, std::size_t hit_room, PositionAt position_at,
                                                       KeyAt key_at, std::span<const Box<Real, Dim>> boxes,
                                                       const CellFloor<Real, Dim>& floor) {
        const std::size_t padded = m + kPadding;
        columns_ = scratch_.lay_out_for(padded, hit_room);
        for (std::size_t r = 0; r < m; ++r) {
            const std::uint32_t position = position_at(r);
            const Box<Real, Dim>& box = boxes[position];
            std::uint32_t inside = 0;
            for (int k = 0; k < Dim; ++k) {
                columns_.min[k][r] = to_float(box.min[k]);
                columns_.max[k][r] = to_float(box.max[k]);
                inside |= (box.min[k] >= floor[k] ? 1U : 0U) << k;
            }
            columns_.inside[r] = static_cast<Mask>(inside);
            if constexpr (!std::is_same_v<KeyAt, NoKeys>) columns_.key[r] = key_at(r);
            columns_.position[r] = position;
        }
        for (std::size_t r = m; r < padded; ++r) {
            for (int k = 0; k < Dim; ++k) {
                // NaN: no comparison with it holds, whatever the box it is tested against.
                columns_.min[k][r] = std::numeric_limits<float>::quiet_NaN();
                columns_.max[k][r] = -std::numeric_limits<float>::infinity();
            }
            columns_.inside[r] = 0;
            columns_.key[r] = ~std::uint32_t{0};  // above the key of any finite max
            columns_.position[r] = 0;
        }
    }

    // Through memcpy: the arrays are not aligned to the lanes' width.
    template <class Lanes, class Value>
    static void load(Lanes& lanes, const Value* from) noexcept {
        std::memcpy(&lanes, from, sizeof lanes);
    }

    // The sweep on x: box i against the boxes after it whose key does not pass the key of its
    // max x, a group of lanes at a time. Keys never decrease along the order, so once a group
    // starts past that key no later box reaches i on x; within a group, min_j <= max_i drops
    // the others. A box j that reaches i has min_j <= max_i, so key_j <= key(to_float(max_i)):
    // the scan goes far enough. The other end, max_j >= min_i, needs no test: with float boxes
    // equal keys are equal values, so min_i <= min_j <= max_j; with double boxes a disorder
    // hidden by equal keys can pass the float test, which the exact test then settles.
    template <class Report>
    void sweep(std::size_t m, std::span<const Box<Real, Dim>> boxes, Report& report) const {
#if SMB_SWEEP_AVX2
        if (cpu_has_avx2()) {
            sweep_avx2(m, boxes, report);
            return;
        }
#endif
        sweep_in_lanes<4>(m, boxes, report);
    }

    // Every box i against every box after it, a group of lanes at a time, on all axes both ways
    // (no order to lean on); the lanes past m hold the padding, which no test passes. The rows
    // only write the hits down, without a branch (append_set_lanes); the report follows. A
    // branch on each group's hits mispredicted about once a group in four.
    template <class Report>
    void test_all_pairs(std::size_t m, std::span<const Box<Real, Dim>> boxes, Report& report,
                        std::vector<std::uint32_t>& home) {
        SMB_ASSERT(m <= kMostPaired, "a cell tested pair by pair packs two local numbers in 31 bits");
        std::size_t count = 0;
#if SMB_SWEEP_AVX2
        if (cpu_has_avx2()) {
            count = pair_rows_avx2(m);
        } else {
            count = pair_rows_in_lanes<4>(m);
        }
#else
        count = pair_rows_in_lanes<4>(m);
#endif
        const std::uint32_t* position = columns_.position;
        const std::uint32_t* hits = columns_.hits;
        for (std::size_t t = 0; t < count; ++t) {
            const std::uint32_t i = hits[t] >> 16;
            const std::uint32_t j = hits[t] & 0xFFFFU;
            if constexpr (kExactLanes && std::invocable<Report&, std::uint32_t, std::uint32_t, bool>) {
                // Exact input (an infinite margin) has nothing to settle: the test is skipped.
                report(position[i], position[j], settles() && overlap_by_margin(i, j));
            } else if (kExactLanes || overlaps(boxes[position[i]], boxes[position[j]])) {
                report(position[i], position[j]);
            }
        }
        append_home(m, home);
    }

    /// Whether the margin can settle anything: exact input has an infinite one.
    [[nodiscard]] bool settles() const noexcept { return sure_margin_ != std::numeric_limits<float>::infinity(); }

    // Whether laid-out boxes i and j overlap by at least the sure margin on every axis, read
    // from the columns the rows just read (in L1), without a branch.
    [[nodiscard]] bool overlap_by_margin(std::uint32_t i, std::uint32_t j) const noexcept {
        bool by_margin = true;
        for (int k = 0; k < Dim; ++k) {
            const float* min = columns_.min[k];
            const float* max = columns_.max[k];
            by_margin &= (max[j] - min[i] >= sure_margin_) & (max[i] - min[j] >= sure_margin_);
        }
        return by_margin;
    }

    // Every box whose lower corner lies in the cell, in the order of the layout (x order when
    // swept, as registered for the pair test); a branch here would guess wrong for one box in
    // four. Gathered apart first: growing `home` by m and back would make it outgrow the
    // capacity reserved for it, at the last cells.
    void append_home(std::size_t m, std::vector<std::uint32_t>& home) {
        if (own_home_.size() < m) own_home_.resize(m);
        std::uint32_t* out = own_home_.data();
        for (std::size_t r = 0; r < m; ++r) {
            *out = columns_.position[r];
            out += columns_.inside[r] == static_cast<Mask>(kAllInside) ? 1 : 0;
        }
        home.insert(home.end(), own_home_.data(), out);
    }

#if SMB_SWEEP_AVX2
    template <class Report>
    [[gnu::target("avx2")]] void sweep_avx2(std::size_t m, std::span<const Box<Real, Dim>> boxes,
                                            Report& report) const {
        sweep_in_lanes<8>(m, boxes, report);
    }
    [[gnu::target("avx2,popcnt")]] std::size_t pair_rows_avx2(std::size_t m) {
        return pair_rows_in_lanes<8>(m);
    }
#endif

    /// One bit for each of the candidates j..j+Lanes-1 that box i (its `own` inside bits, its
    /// `low` and `high` corners) may report: tested both ways on every axis, except the lower
    /// end on x when swept.
    template <std::size_t Lanes, bool Swept>
    [[gnu::always_inline]] inline unsigned lanes_hit(std::size_t j, Mask own, const std::array<float, Dim>& low,
                                                     const std::array<float, Dim>& high) const {
        using FloatLanes = typename SweepLanes<Lanes>::Floats;
        using MaskLanes = typename SweepLanes<Lanes>::Masks;
        MaskLanes others;
        load(others, columns_.inside + j);
        MaskLanes hit = (others | own) == static_cast<Mask>(kAllInside);
        for (int k = 0; k < Dim; ++k) {
            FloatLanes lower;
            load(lower, columns_.min[k] + j);
            hit &= lower <= high[k];
            if (!Swept || k > 0) {
                FloatLanes upper;
                load(upper, columns_.max[k] + j);
                hit &= upper >= low[k];
            }
        }
        return lane_bits<Lanes>(hit);
    }

    /// The corners of row i's box, tested against every group of candidates of its row.
    [[gnu::always_inline]] inline void row_corners(std::size_t i, std::array<float, Dim>& low,
                                                   std::array<float, Dim>& high) const noexcept {
        for (int k = 0; k < Dim; ++k) {
            low[k] = columns_.min[k][i];
            high[k] = columns_.max[k][i];
        }
    }

    template <std::size_t Lanes, class Report>
    [[gnu::always_inline]] inline void sweep_in_lanes(std::size_t m, std::span<const Box<Real, Dim>> boxes,
                                                      Report& report) const {
        const std::uint32_t* key = columns_.key;
        const Mask* inside = columns_.inside;
        const std::uint32_t* position = columns_.position;
        for (std::size_t i = 0; i < m; ++i) {
            const std::uint32_t stop = monotone_key(columns_.max[0][i]);
            std::array<float, Dim> low{}, high{};  // low[0] unused, see sweep()
            row_corners(i, low, high);
            for (std::size_t j = i + 1; key[j] <= stop; j += Lanes) {
                unsigned bits = lanes_hit<Lanes, true>(j, inside[i], low, high);
                while (bits != 0) {
                    const std::uint32_t other = position[j + static_cast<std::size_t>(std::countr_zero(bits))];
                    bits &= bits - 1;
                    if (kExactLanes || overlaps(boxes[position[i]], boxes[other])) report(position[i], other);
                }
            }
        }
    }

    /// Writes the hit list with every pair (i << 16 | j, i < j) that passes the lanes' test, row by
    /// row; returns their number.
    template <std::size_t Lanes>
    [[gnu::always_inline]] inline std::size_t pair_rows_in_lanes(std::size_t m) {
        using MaskLanes = typename SweepLanes<Lanes>::Masks;
        MaskLanes lane{};
        for (std::size_t l = 0; l < Lanes; ++l) lane[l] = static_cast<Mask>(l);
        std::uint32_t* const first = columns_.hits;
        std::uint32_t* out = first;
        for (std::size_t i = 0; i < m; ++i) {
            std::array<float, Dim> low{}, high{};
            row_corners(i, low, high);
            const Mask own = columns_.inside[i];
            MaskLanes pair = lane + static_cast<Mask>((i << 16) | (i + 1));
            for (std::size_t j = i + 1; j < m; j += Lanes) {
                out = append_set_lanes<Lanes>(out, lanes_hit<Lanes, false>(j, own, low, high), pair);
                pair += static_cast<Mask>(Lanes);
            }
        }
        return static_cast<std::size_t>(out - first);
    }

    // Boxes whose keys are equal arrive in an order that depends on the previous step; ordering
    // them by exact coordinate and id makes the reported order a function of the boxes alone,
    // so that detecting twice without changes reports the same list. Such runs are rare outside
    // scenes of equal coordinates, where they are short.
    template <class Id>
    static void order_equal_keys(std::uint64_t* order, std::size_t m, std::span<const std::uint32_t> entries,
                                 std::span<const Box<Real, Dim>> boxes, std::span<const Id> ids) {
        std::size_t run = 0;
        for (std::size_t i = 1; i <= m; ++i) {
            if (i < m && (order[i] >> 32) == (order[run] >> 32)) continue;
            if (i - run > 1) {
                std::sort(order + run, order + i, [&](std::uint64_t x, std::uint64_t y) {
                    const std::uint32_t a = entries[x & 0xFFFFFFFFU];
                    const std::uint32_t b = entries[y & 0xFFFFFFFFU];
                    if (boxes[a].min[0] != boxes[b].min[0]) return boxes[a].min[0] < boxes[b].min[0];
                    return ids[a] < ids[b];
                });
            }
            run = i;
        }
    }

    // DIS with the single increment 1: the cell's list follows last step's order, so only the
    // boxes that moved past a neighbour, and those registered here from a neighbouring cell,
    // are out of place. The keys carry the local numbers, so a move shifts 8 bytes, not a box.
    static std::size_t insertion_sort(std::uint64_t* keys, std::size_t m) {
        std::size_t moves = 0;
        for (std::size_t i = 1; i < m; ++i) {
            const std::uint64_t moving = keys[i];
            std::size_t j = i;
            while (j > 0 && moving < keys[j - 1]) {
                keys[j] = keys[j - 1];
                --j;
            }
            keys[j] = moving;
            moves += i - j;
        }
        return moves;
    }

    std::vector<std::uint64_t> order_;
    CellScratch<Dim> scratch_;
    // The cell's boxes, one array per coordinate (as floats), in x order for the sweep or as
    // registered for the all-pairs test, padded with kPadding boxes that reach nothing (min NaN,
    // key above every real key) so that the last group of lanes may read past the end; and the
    // pairs the lanes passed, as (i << 16 | j), in row order.
    typename CellScratch<Dim>::Columns columns_;
    float sure_margin_ = std::numeric_limits<float>::infinity();
    std::vector<std::uint32_t> own_home_;  // the cell's home boxes, on their way to `home`
};

}  // namespace smb::detail
