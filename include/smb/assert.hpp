// SPDX-License-Identifier: MIT
#pragma once
// Internal consistency checks of smb report through a handler the application may replace
// (to log, to break into a debugger, or to throw in tests). Bad input never reaches it: that
// is reported by exceptions (smb/errors.hpp). The default handler prints and aborts.

namespace smb {

using AssertHandler = void (*)(const char* condition, const char* message, const char* file, int line);

/// Installs `handler` (nullptr restores the default) and returns the previous one.
AssertHandler set_assert_handler(AssertHandler handler) noexcept;

}  // namespace smb
