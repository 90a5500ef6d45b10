// SPDX-License-Identifier: MIT
#pragma once
// Outputs written half way, removed when a signal ends the program: a crash or a Ctrl-C must not
// leave a .<name>.smb-partial-XXXXXX file behind. Destructors do not run then, so the handler
// itself removes them, with unlink() only (async-signal-safe), and then lets the signal do what
// it did before: end the program, or reach the handler installed before (a sanitizer's).

#include <string>

namespace smb::io {

/// Remembers `path` for the signal handlers (installed at the first call) and returns a slot
/// for forget_partial_file, or -1 where no slot is free or the path is too long (then only the
/// destructor of its OutputFile removes it).
[[nodiscard]] int remember_partial_file(const std::string& path);

/// The file in `slot` is no longer partial (committed or removed); -1 does nothing.
void forget_partial_file(int slot) noexcept;

}  // namespace smb::io
