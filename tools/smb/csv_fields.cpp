// SPDX-License-Identifier: MIT
#include "csv_fields.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace smb::io {

namespace {

[[noreturn]] void fail(std::string_view column, std::string_view field, const std::string& what) {
    throw std::invalid_argument(std::string(column) + " " + quoted(field) + " " + what);
}

}  // namespace

// Bytes outside printable ASCII are shown as \xHH: a NUL would otherwise cut the message
// short (what() is a C string) and other control bytes would garble the terminal.
std::string quoted(std::string_view text) {
    constexpr std::size_t shown = 40;
    constexpr char hex_digits[] = "0123456789abcdef";
    std::string result = "'";
    for (const char c : text.substr(0, shown)) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f) {
            result += c;
        } else {
            result += "\\x";
            result += hex_digits[byte >> 4];
            result += hex_digits[byte & 0xf];
        }
    }
    if (text.size() > shown) result += "...";
    result += "'";
    return result;
}

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
    fields.clear();
    for (;;) {
        const std::size_t comma = line.find(',');
        fields.push_back(line.substr(0, comma));
        if (comma == std::string_view::npos) return;
        line.remove_prefix(comma + 1);
    }
}

std::string_view trim(std::string_view text) {
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string_view::npos) return {};
    const auto last = text.find_last_not_of(" \t");
    return text.substr(first, last - first + 1);
}

std::uint64_t parse_unsigned(std::string_view field, std::string_view column) {
    const std::string_view text = trim(field);
    if (text.empty()) throw std::invalid_argument("empty " + std::string(column));
    if (text.front() == '-') fail(column, text, "is negative");
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error == std::errc::result_out_of_range) fail(column, text, "does not fit in 64 bits");
    if (error != std::errc{} || end != text.data() + text.size()) fail(column, text, "is not an unsigned integer");
    return value;
}

double parse_finite_double(std::string_view field, std::string_view column) {
    const std::string_view text = trim(field);
    if (text.empty()) throw std::invalid_argument("empty " + std::string(column));
    // from_chars takes '-' but not '+'; accept both signs, never two.
    std::string_view digits = text;
    if (digits.front() == '+') {
        digits.remove_prefix(1);
        if (digits.empty() || digits.front() == '+' || digits.front() == '-') fail(column, text, "is not a number");
    }
    double value = 0;
    const auto [end, error] =
        std::from_chars(digits.data(), digits.data() + digits.size(), value, std::chars_format::general);
    if (error == std::errc::invalid_argument || end != digits.data() + digits.size())
        fail(column, text, "is not a number");
    if (error == std::errc::result_out_of_range) {
        // libstdc++ reports underflow like overflow; strtod tells them apart and rounds
        // subnormals correctly.
        const std::string copy(digits);
        errno = 0;
        value = std::strtod(copy.c_str(), nullptr);
        if (std::isinf(value) || std::abs(value) == HUGE_VAL) fail(column, text, "is too large for a double");
    }
    if (!std::isfinite(value)) fail(column, text, "is not finite");
    return value;
}

}  // namespace smb::io
