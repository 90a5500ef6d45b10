// SPDX-License-Identifier: MIT
#pragma once
// Field-level parsing shared by the scene and pair CSV readers, and the writers' flush size.
// Problems are thrown as std::invalid_argument with a message naming the column; the readers add
// file and line.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace smb::io {

/// The bytes a CSV writer gathers before it hands them to the stream: large writes, few calls.
inline constexpr std::size_t csv_flush_threshold = std::size_t{1} << 20;

/// Splits a line at commas into `fields` (cleared first). Quoting is not part of our formats.
void split_fields(std::string_view line, std::vector<std::string_view>& fields);

/// `text` between single quotes for a message: its first 40 bytes, those outside printable
/// ASCII written as \xHH, and "..." where it was cut.
[[nodiscard]] std::string quoted(std::string_view text);

/// Drops surrounding spaces and tabs.
[[nodiscard]] std::string_view trim(std::string_view text);

/// A decimal unsigned 64-bit integer: no sign, no spaces inside, no overflow.
[[nodiscard]] std::uint64_t parse_unsigned(std::string_view field, std::string_view column);

/// A finite decimal number rounded to the nearest double (std::from_chars), optionally signed.
/// NaN and infinities are rejected; values below the smallest subnormal round to zero.
[[nodiscard]] double parse_finite_double(std::string_view field, std::string_view column);

}  // namespace smb::io
