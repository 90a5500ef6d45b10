// SPDX-License-Identifier: MIT
// libFuzzer target: changes to an array of boxes on hostile coordinates, each followed by a
// Detector call checked against brute force (see detector_ops_check.hpp). A broken promise
// throws, which libFuzzer reports as a crash.

#include <cstddef>
#include <cstdint>

#include "detector_ops_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    smb::fuzz::check_detector_operations(data, size);
    return 0;
}
