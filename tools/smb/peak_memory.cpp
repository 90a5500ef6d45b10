// SPDX-License-Identifier: MIT
#include "peak_memory.hpp"

#if defined(__unix__) || defined(__APPLE__)
#include <sys/resource.h>
#endif

namespace smb::cli {

std::optional<std::size_t> peak_resident_bytes() {
#if defined(__unix__) || defined(__APPLE__)
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss <= 0) return std::nullopt;
    const auto reported = static_cast<std::size_t>(usage.ru_maxrss);
#if defined(__APPLE__)
    return reported;  // macOS reports bytes
#else
    return reported * 1024;  // Linux and the BSDs report kilobytes
#endif
#else
    return std::nullopt;
#endif
}

}  // namespace smb::cli
