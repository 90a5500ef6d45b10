// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string_view>
#include <vector>

namespace smb::io {

/// Reads a stream line by line through a large buffer, without the per-line allocation of
/// std::getline. Lines end at '\n'; a '\r' before it (CRLF files) is dropped, and a last line
/// without a final newline is still a line.
class LineReader {
public:
    explicit LineReader(std::istream& in, std::size_t chunk_size = std::size_t{1} << 20);

    /// The next line, valid until the following call; empty optional at the end of input.
    std::optional<std::string_view> next();

    /// 1-based number of the line last returned.
    [[nodiscard]] std::uint64_t line_number() const noexcept { return line_number_; }

private:
    bool refill();

    std::istream& in_;
    std::size_t chunk_size_;
    std::vector<char> buffer_;
    std::size_t begin_ = 0;  // first unread byte in buffer_
    std::size_t end_ = 0;    // one past the last valid byte
    bool input_done_ = false;
    std::uint64_t line_number_ = 0;
};

}  // namespace smb::io
