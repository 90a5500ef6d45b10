// SPDX-License-Identifier: MIT
#pragma once

#include <cstddef>
#include <optional>

namespace smb::cli {

/// The most resident memory this process has held so far, in bytes, as the operating system
/// counts it (getrusage); empty where that is not available.
[[nodiscard]] std::optional<std::size_t> peak_resident_bytes();

}  // namespace smb::cli
