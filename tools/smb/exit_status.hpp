// SPDX-License-Identifier: MIT
#pragma once
// The exit statuses of smb, in one place: main() returns them, `smb --help` and
// tools/smb/README.md state them (tests/tool/test_cli_arguments.cpp holds the three to one another).

namespace smb::cli::exit_status {

inline constexpr int success = 0;
/// Bad input (a malformed file, impossible parameters) or an I/O failure.
inline constexpr int failure = 1;
/// `smb run`: a checked step's pairs differ from the grid reference.
inline constexpr int mismatch = 2;
/// Bad arguments: an unknown command or option, a missing or invalid value (EX_USAGE of
/// sysexits.h).
inline constexpr int usage = 64;

/// The text that `smb --help` ends with.
inline constexpr const char* summary =
    "Exit status: 0 success; 1 bad input or I/O failure; 2 a checked step of 'smb run' differs "
    "from the reference; 64 bad arguments (unknown command or option, missing or invalid value).";

}  // namespace smb::cli::exit_status
