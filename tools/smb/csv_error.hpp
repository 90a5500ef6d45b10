// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace smb::io {

/// Malformed CSV input. what() reads "source:line: problem", the form compilers use, so editors
/// and terminals can jump to the line.
class CsvError : public std::runtime_error {
public:
    CsvError(const std::string& source, std::uint64_t line, const std::string& problem)
        : std::runtime_error(source + ":" + std::to_string(line) + ": " + problem), line_(line) {}

    [[nodiscard]] std::uint64_t line() const noexcept { return line_; }

private:
    std::uint64_t line_;
};

}  // namespace smb::io
