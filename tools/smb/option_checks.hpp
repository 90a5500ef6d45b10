// SPDX-License-Identifier: MIT
#pragma once
// Checks of numeric options whose messages name the bound and the value as the user wrote them
// ("must be at least 1, not 0.1"): CLI11's own Range prints both through std::to_string
// ("not in range 1.000000 to 1000000000000.000000").

#include <CLI/CLI.hpp>

namespace smb::cli {

/// The value lies in [low, high].
[[nodiscard]] CLI::Validator in_closed_range(double low, double high);
/// The value lies in [low, high).
[[nodiscard]] CLI::Validator in_half_open_range(double low, double high);
/// The value is at least `low`.
[[nodiscard]] CLI::Validator at_least(double low);
/// The value is greater than `low`.
[[nodiscard]] CLI::Validator greater_than(double low);
/// The value is not negative; nothing said in --help, where the type (UINT) says it already.
[[nodiscard]] CLI::Validator not_negative();

}  // namespace smb::cli
