// SPDX-License-Identifier: MIT
#pragma once
// The vector lanes the cell check and the skin list compare boxes in (GCC vector extensions):
// four or eight floats at once, the choice made when the program runs, and the two ways a test's
// lanes come out: as bits, and packed, the set lanes' values to the front.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SMB_LANES_AVX2 1
#include <immintrin.h>
#else
#define SMB_LANES_AVX2 0
#endif

namespace smb::detail {

/// Lanes of floats (and of masks of the same width) that one vector compares at once: four fill an
/// SSE (or NEON) register, eight an AVX2 one.
template <std::size_t Lanes>
struct FloatLanes;
template <>
struct FloatLanes<4> {
    using Floats [[gnu::vector_size(16)]] = float;
    using Masks [[gnu::vector_size(16)]] = std::int32_t;
};
template <>
struct FloatLanes<8> {
    using Floats [[gnu::vector_size(32)]] = float;
    using Masks [[gnu::vector_size(32)]] = std::int32_t;
};

// Eight lanes where the processor has AVX2 (chosen when the program runs: the library is built
// for the baseline x86-64), four elsewhere. GCC only: clang 14, which builds the fuzzers,
// takes the four lanes. The environment variable SMB_NO_AVX2 (any value) forces the four
// lanes, so that the tests and benchmarks can check and time them on an AVX2 machine.
#if SMB_LANES_AVX2
[[nodiscard]] inline bool cpu_has_avx2() noexcept {
    static const bool has = __builtin_cpu_supports("avx2") != 0 && std::getenv("SMB_NO_AVX2") == nullptr;
    return has;
}
#endif

/// One bit per lane whose mask is set (all ones): a single instruction on x86-64, where the
/// compiler would otherwise take the lanes out one by one.
template <std::size_t Lanes>
[[nodiscard]] inline unsigned lane_bits(const typename FloatLanes<Lanes>::Masks& hit) noexcept {
    unsigned bits = 0;
    for (std::size_t lane = 0; lane < Lanes; ++lane) bits |= static_cast<unsigned>(hit[lane] & 1) << lane;
    return bits;
}
#if defined(__x86_64__) && defined(__GNUC__)
template <>
[[nodiscard]] inline unsigned lane_bits<4>(const FloatLanes<4>::Masks& hit) noexcept {
    return static_cast<unsigned>(__builtin_ia32_movmskps(__builtin_bit_cast(FloatLanes<4>::Floats, hit)));
}
#endif
#if SMB_LANES_AVX2
template <>
[[gnu::target("avx2")]] [[nodiscard]] inline unsigned lane_bits<8>(const FloatLanes<8>::Masks& hit) noexcept {
    return static_cast<unsigned>(__builtin_ia32_movmskps256(__builtin_bit_cast(FloatLanes<8>::Floats, hit)));
}
#endif

/// Writes the values of the lanes set in `bits` to `out`, in lane order, and returns the end of
/// what it wrote; the Lanes slots from `out` on may all be written. No branch on the bits.
template <std::size_t Lanes>
[[gnu::always_inline]] inline std::uint32_t* append_set_lanes(
    std::uint32_t* out, unsigned bits, const typename FloatLanes<Lanes>::Masks& values) noexcept {
    for (std::size_t lane = 0; lane < Lanes; ++lane) {
        *out = static_cast<std::uint32_t>(values[lane]);
        out += (bits >> lane) & 1U;
    }
    return out;
}
#if SMB_LANES_AVX2
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
                                                                         const FloatLanes<8>::Masks& values) noexcept {
    const __m256i order = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kSetLaneOrder[bits])));
    const __m256i packed = _mm256_permutevar8x32_epi32(__builtin_bit_cast(__m256i, values), order);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), packed);
    return out + std::popcount(bits);
}
#endif

}  // namespace smb::detail
