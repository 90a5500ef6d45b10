// SPDX-License-Identifier: MIT
#pragma once
// Heap bytes allocated by the method under measurement. smb_compare replaces glibc's malloc
// family with thin wrappers (glibc supports this: "Replacing malloc" in its manual) that count
// the usable size of every block allocated or freed while counting is on. The harness turns
// counting on only around a method's build() and step() calls, so the count is the method's
// own memory: its persistent structures plus whatever it allocates transiently.

#include <cstddef>

namespace smb::bench::heap_meter {

/// False in builds where another allocator wrapper owns malloc (sanitizers): then nothing is
/// counted and the report falls back to resident memory.
[[nodiscard]] bool available() noexcept;

/// Turns counting on or off. Blocks freed while counting is on are subtracted whoever
/// allocated them, so the harness must not free its own memory while counting.
void set_counting(bool on) noexcept;

/// Bytes allocated while counting and not yet freed.
[[nodiscard]] std::size_t live_bytes() noexcept;
/// The largest live_bytes() ever reached.
[[nodiscard]] std::size_t peak_bytes() noexcept;

/// Counts the method's work for the lifetime of the object.
class CountingScope {
public:
    CountingScope() noexcept { set_counting(true); }
    ~CountingScope() { set_counting(false); }
    CountingScope(const CountingScope&) = delete;
    CountingScope& operator=(const CountingScope&) = delete;
};

}  // namespace smb::bench::heap_meter
