// SPDX-License-Identifier: MIT
#include "option_checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace smb::cli {

namespace {

std::optional<double> number_in(const std::string& text) {
    double value = 0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    if (first != last && *first == '+') ++first;  // from_chars takes '-' only
    const auto [end, error] = std::from_chars(first, last, value);
    if (error != std::errc{} || end != last || !std::isfinite(value)) return std::nullopt;
    return value;
}

/// A validator that accepts a number for which `accepts` holds and otherwise says "must be
/// <requirement>, not <the text as given>". The bounds print in fmt's shortest form;
/// `description` follows the value's type in --help.
CLI::Validator number_check(std::string requirement, std::string description, std::function<bool(double)> accepts) {
    return CLI::Validator(
        [requirement, accepts](std::string& text) -> std::string {
            const auto value = number_in(text);
            if (!value) return fmt::format("must be a number {}, not '{}'", requirement, text);
            if (!accepts(*value)) return fmt::format("must be {}, not {}", requirement, text);
            return {};
        },
        std::move(description));
}

}  // namespace

CLI::Validator in_closed_range(double low, double high) {
    const std::string range = fmt::format("in [{}, {}]", low, high);
    return number_check(range, range, [low, high](double value) { return low <= value && value <= high; });
}

CLI::Validator in_half_open_range(double low, double high) {
    const std::string range = fmt::format("in [{}, {})", low, high);
    return number_check(range, range, [low, high](double value) { return low <= value && value < high; });
}

CLI::Validator at_least(double low) {
    const std::string requirement = fmt::format("at least {}", low);
    return number_check(requirement, requirement, [low](double value) { return value >= low; });
}

CLI::Validator greater_than(double low) {
    const std::string requirement = fmt::format("greater than {}", low);
    return number_check(requirement, requirement, [low](double value) { return value > low; });
}

CLI::Validator not_negative() {
    // For unsigned options, which CLI11 would otherwise take "-5" for, wrapped around 2^64.
    return number_check("at least 0", "", [](double value) { return value >= 0; });
}

}  // namespace smb::cli
