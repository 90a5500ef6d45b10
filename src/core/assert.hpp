// SPDX-License-Identifier: MIT
#pragma once

#include "smb/assert.hpp"

namespace smb::detail {

[[noreturn]] void assert_failed(const char* condition, const char* message, const char* file, int line);

}  // namespace smb::detail

// Kept on in every build type: the checks guard cheap invariants only; the costly ones are
// behind SMB_VALIDATE.
#define SMB_ASSERT(cond, msg)                                                      \
    do {                                                                           \
        if (!(cond)) ::smb::detail::assert_failed(#cond, msg, __FILE__, __LINE__); \
    } while (false)
