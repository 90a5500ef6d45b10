// SPDX-License-Identifier: MIT
// libFuzzer target: sequences of World operations on hostile coordinates against a mirror
// model (see world_ops_check.hpp). A broken promise throws, which libFuzzer reports as a crash.

#include <cstddef>
#include <cstdint>

#include "world_ops_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    smb::fuzz::check_world_operations(data, size);
    return 0;
}
