// SPDX-License-Identifier: MIT
#pragma once
// The pair CSV of the smb conventions: header `frame,a,b`, one row per overlapping pair with
// a < b, rows sorted by (frame, a, b); a frame without contacts has no rows.

#include <compare>
#include <cstdint>
#include <istream>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "smb/pair.hpp"

namespace smb::io {

/// Writes the pair CSV, buffering the text in large blocks.
class PairWriter {
public:
    /// `header`: the first line (without newline); `smb join` writes `frame,left,right`.
    explicit PairWriter(std::ostream& out, std::string_view header = "frame,a,b");
    ~PairWriter();
    PairWriter(const PairWriter&) = delete;
    PairWriter& operator=(const PairWriter&) = delete;

    /// Writes the pairs of one frame; they must be sorted (sort_pairs) and frames increasing.
    void write_frame(std::uint64_t frame, std::span<const Pair> pairs);
    /// Hands everything buffered to the stream; throws std::runtime_error if the stream failed.
    void flush();

private:
    std::ostream& out_;
    std::string buffer_;
};

/// One row of a pair CSV.
struct FramePair {
    std::uint64_t frame = 0;
    BoxId a = 0;
    BoxId b = 0;

    friend auto operator<=>(const FramePair&, const FramePair&) = default;
};

/// Reads a whole pair CSV (for tests and comparisons), checking the header, the fields, a < b
/// and the row order; problems are thrown as CsvError.
[[nodiscard]] std::vector<FramePair> read_pair_csv(std::istream& in, const std::string& source_name);

}  // namespace smb::io
