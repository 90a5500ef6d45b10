// SPDX-License-Identifier: MIT
// libFuzzer target: the scene CSV reader of the smb tool on arbitrary bytes (see
// scene_csv_check.hpp). Anything but a CsvError, or a broken promise, escapes as a crash.

#include <cstddef>
#include <cstdint>

#include "scene_csv_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    smb::fuzz::check_scene_csv(data, size);
    return 0;
}
