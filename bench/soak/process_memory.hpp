// SPDX-License-Identifier: MIT
#pragma once
// The process's memory as the kernel sees it, for the soak and explosion runs (Linux).

#include <sys/resource.h>
#include <unistd.h>

#include <cstddef>
#include <fstream>

namespace smb::soak {

/// Resident memory now.
inline std::size_t resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t total_pages = 0;
    std::size_t resident_pages = 0;
    statm >> total_pages >> resident_pages;
    return resident_pages * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

/// Highest resident memory so far.
inline std::size_t peak_resident_bytes() {
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux counts in KiB
}

}  // namespace smb::soak
