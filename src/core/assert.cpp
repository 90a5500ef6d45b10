// SPDX-License-Identifier: MIT
#include "core/assert.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace smb {
namespace {

void default_handler(const char* condition, const char* message, const char* file, int line) {
    std::fprintf(stderr, "smb: internal check failed: %s (%s) at %s:%d\n", condition, message, file, line);
}

std::atomic<AssertHandler> g_handler{&default_handler};

}  // namespace

AssertHandler set_assert_handler(AssertHandler handler) noexcept {
    return g_handler.exchange(handler != nullptr ? handler : &default_handler);
}

namespace detail {

void assert_failed(const char* condition, const char* message, const char* file, int line) {
    g_handler.load()(condition, message, file, line);
    // A handler that returns (rather than throwing or exiting) still must not let a broken
    // structure go on producing wrong pairs.
    std::abort();
}

}  // namespace detail
}  // namespace smb
