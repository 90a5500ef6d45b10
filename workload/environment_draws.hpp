// SPDX-License-Identifier: MIT
#pragma once
// The random draws and boundary rules of the paper's environment, shared by DynamicEnvironment
// (every box) and EnvironmentShare (the boxes of one rank): both must draw the same numbers from
// the same stream in the same order, or a rank's share would not be the serial scene's rows.
//
// The draws use only the raw 64-bit output of the engine, never the standard distributions:
// those are implementation-defined, and a scene must be the same everywhere.

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace smb::workload::draws {

inline constexpr double two_pow_minus_52 = 0x1.0p-52;
inline constexpr double two_pow_minus_53 = 0x1.0p-53;

/// Uniform in [0, 1).
template <class Engine>
double unit_interval(Engine& rng) {
    return static_cast<double>(rng() >> 11) * two_pow_minus_53;
}

/// Uniform in the open interval (-1, 1), symmetric about 0: the odd multiples of 2^-52 in
/// (-1, 1) are all exactly representable, so no rounding can reach either bound.
template <class Engine>
double symmetric_unit(Engine& rng) {
    const auto k = static_cast<std::int64_t>(rng() >> 12);  // [0, 2^52)
    const std::int64_t odd = 2 * k + 1 - (std::int64_t{1} << 52);
    return static_cast<double>(odd) * two_pow_minus_52;
}

/// Uniform index in [0, count), by the multiply-high reduction (bias below 2^-40 here).
template <class Engine>
std::size_t uniform_index(Engine& rng, std::size_t count) {
    __extension__ using wide = unsigned __int128;
    return static_cast<std::size_t>((static_cast<wide>(rng()) * count) >> 64);
}

template <class Engine>
double uniform_between(Engine& rng, double low, double high) {
    return std::min(high, low + (high - low) * unit_interval(rng));
}

/// Mirrors `value` back into [low, high] at the bound it crossed; the clamp only acts when the
/// overshoot is larger than the interval itself.
inline double reflect_into(double value, double low, double high) {
    if (value < low) value = low + (low - value);
    if (value > high) value = high - (value - high);
    return std::clamp(value, low, high);
}

/// Numbers drawn per box placed (a side, then a centre, per axis) and per box moved (a side
/// fraction, then a centre fraction, per axis).
inline constexpr std::size_t per_box(int dim) { return 2 * static_cast<std::size_t>(dim); }

}  // namespace smb::workload::draws
