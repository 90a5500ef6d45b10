// SPDX-License-Identifier: MIT
#pragma once
// The candidate test of the grid peers: one box against a run of boxes kept as separate arrays of
// floats (all lower x, all lower y, ..., all upper z), 4 or 8 of them in one vector compare,
// the positions of those that overlap packed to the front of an output buffer. No branch depends
// on a candidate, so the cost is the same whether it overlaps or not.
//
// The build targets baseline x86-64; the 8-lane (AVX2) version is compiled in functions marked
// with that target and chosen when the program runs (best_lanes()). There is no 16-lane AVX-512
// version: the machine the comparison runs on has no AVX-512 to test it.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string_view>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SMB_BENCH_WIDE_LANES 1
#include <immintrin.h>
#else
#define SMB_BENCH_WIDE_LANES 0
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#endif

// The helpers below pass vectors by value, but every one is inlined into a function compiled for
// its lanes, so no vector crosses a call and GCC's note on the vector ABI does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace smb::bench::grid_lanes {

/// The boxes a run is taken from, one array per coordinate, each readable Lanes - 1 floats past
/// the last box.
template <int Dim>
struct Columns {
    std::array<const float*, Dim> min{};
    std::array<const float*, Dim> max{};
};

template <std::size_t Lanes>
struct Vectors {
    using Floats [[gnu::vector_size(4 * Lanes)]] = float;
    using Ints [[gnu::vector_size(4 * Lanes)]] = std::int32_t;
};

/// One box's corners, each coordinate copied into every lane.
template <std::size_t Lanes, int Dim>
struct Query {
    std::array<typename Vectors<Lanes>::Floats, Dim> min;
    std::array<typename Vectors<Lanes>::Floats, Dim> max;
};

template <std::size_t Lanes, int Dim>
[[gnu::always_inline]] inline Query<Lanes, Dim> splat(const std::array<float, Dim>& min,
                                                      const std::array<float, Dim>& max) noexcept {
    Query<Lanes, Dim> query;
    for (int k = 0; k < Dim; ++k) {
        query.min[k] = typename Vectors<Lanes>::Floats{} + min[k];
        query.max[k] = typename Vectors<Lanes>::Floats{} + max[k];
    }
    return query;
}

template <std::size_t Lanes>
[[gnu::always_inline]] inline typename Vectors<Lanes>::Floats load(const float* from) noexcept {
    typename Vectors<Lanes>::Floats value;
    std::memcpy(&value, from, sizeof value);
    return value;
}

/// One bit per lane whose mask is set (masks are all ones or all zeros).
template <std::size_t Lanes>
[[gnu::always_inline]] inline unsigned lane_bits(const typename Vectors<Lanes>::Ints& hit) noexcept {
#if defined(__SSE2__)
    static_assert(Lanes == 4);
    return static_cast<unsigned>(_mm_movemask_ps(__builtin_bit_cast(__m128, hit)));
#else
    unsigned bits = 0;
    for (std::size_t lane = 0; lane < Lanes; ++lane) bits |= static_cast<unsigned>(hit[lane] & 1) << lane;
    return bits;
#endif
}

/// Writes the lanes of `positions` set in `bits` to `out`, in lane order, and returns the end of
/// what it wrote; it may write all Lanes slots from `out` on.
template <std::size_t Lanes>
[[gnu::always_inline]] inline std::uint32_t* pack(std::uint32_t* out, unsigned bits,
                                                  const typename Vectors<Lanes>::Ints& positions) noexcept {
    for (std::size_t lane = 0; lane < Lanes; ++lane) {
        *out = static_cast<std::uint32_t>(positions[lane]);
        out += (bits >> lane) & 1U;
    }
    return out;
}

#if SMB_BENCH_WIDE_LANES
template <>
[[gnu::target("avx2")]] inline unsigned lane_bits<8>(const Vectors<8>::Ints& hit) noexcept {
    return static_cast<unsigned>(_mm256_movemask_ps(__builtin_bit_cast(__m256, hit)));
}
/// For each byte of lane bits, the numbers of its set lanes, lowest first, one a byte: the
/// permutation that moves those lanes to the front of an AVX2 register.
inline constexpr std::array<std::uint64_t, 256> front_of = [] {
    std::array<std::uint64_t, 256> table{};
    for (unsigned bits = 0; bits < 256; ++bits) {
        unsigned filled = 0;
        for (unsigned lane = 0; lane < 8; ++lane)
            if ((bits >> lane) & 1U) table[bits] |= std::uint64_t{lane} << (8 * filled++);
    }
    return table;
}();

template <>
[[gnu::target("avx2,popcnt")]] inline std::uint32_t* pack<8>(std::uint32_t* out, unsigned bits,
                                                             const Vectors<8>::Ints& positions) noexcept {
    const __m256i order = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(front_of[bits])));
    const __m256i packed = _mm256_permutevar8x32_epi32(__builtin_bit_cast(__m256i, positions), order);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), packed);
    return out + std::popcount(bits);
}

#endif

/// The lanes of one compare: the boxes at [at, at + Lanes) of `columns` that overlap `query`
/// (closed: touching counts) and lie before `to`, their positions appended to `out`.
template <std::size_t Lanes, int Dim>
[[gnu::always_inline]] inline std::uint32_t* test_lanes(const Columns<Dim>& columns, const Query<Lanes, Dim>& query,
                                                        std::uint32_t at, std::uint32_t to,
                                                        std::uint32_t* out) noexcept {
    using Ints = typename Vectors<Lanes>::Ints;
    Ints hit = (load<Lanes>(columns.min[0] + at) <= query.max[0]) & (load<Lanes>(columns.max[0] + at) >= query.min[0]);
    for (int k = 1; k < Dim; ++k)
        hit &= (load<Lanes>(columns.min[k] + at) <= query.max[k]) & (load<Lanes>(columns.max[k] + at) >= query.min[k]);
    const auto left = static_cast<std::int64_t>(to) - static_cast<std::int64_t>(at);
    const unsigned valid = (1U << std::clamp<std::int64_t>(left, 0, Lanes)) - 1;
    Ints positions;
    for (std::size_t lane = 0; lane < Lanes; ++lane) positions[lane] = static_cast<std::int32_t>(at + lane);
    return pack<Lanes>(out, lane_bits<Lanes>(hit) & valid, positions);
}

/// Appends to `out` the position of every box in [from, to) of `columns` that overlaps `query`
/// and returns the new end. The first two compares run whatever the length: most runs are that
/// short, and a loop whose length varies from run to run would cost a mispredicted branch each.
/// `out` needs room for to - from + 2 Lanes, `columns` 2 Lanes floats readable from `from`.
template <std::size_t Lanes, int Dim>
[[gnu::always_inline]] inline std::uint32_t* test_run(const Columns<Dim>& columns, const Query<Lanes, Dim>& query,
                                                      std::uint32_t from, std::uint32_t to,
                                                      std::uint32_t* out) noexcept {
    out = test_lanes<Lanes, Dim>(columns, query, from, to, out);
    out = test_lanes<Lanes, Dim>(columns, query, from + Lanes, to, out);
    for (std::uint32_t at = from + 2 * Lanes; at < to; at += Lanes)
        out = test_lanes<Lanes, Dim>(columns, query, at, to, out);
    return out;
}

/// The widest lanes this processor runs: 8 with AVX2, else 4. The environment variable
/// SMB_BENCH_GRID_LANES=4 forces 4, to time and test both.
[[nodiscard]] inline std::size_t best_lanes() noexcept {
    static const std::size_t lanes = [] {
        std::size_t best = 4;
#if SMB_BENCH_WIDE_LANES
        if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt")) best = 8;
#endif
        if (const char* wanted = std::getenv("SMB_BENCH_GRID_LANES"); wanted && std::string_view(wanted) == "4")
            best = 4;
        return best;
    }();
    return lanes;
}

}  // namespace smb::bench::grid_lanes

#pragma GCC diagnostic pop
