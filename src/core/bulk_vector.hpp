// SPDX-License-Identifier: MIT
#pragma once
// The arrays that follow the number of boxes (a World's store, the ordered copy of the cuts, the
// levels' lists, the skin's boxes): their pages are mapped in one call when a block is allocated.
// A detection writes each of them whole, and the first write of every page is otherwise a fault
// of its own: where a fault is dear (under a hypervisor here, 12 µs a page, so 70 ms for the
// 24 MB copy of a million boxes), the faults of a first detection, or of a step that grows an
// array, cost more than the detection. Mapped at once (MADV_POPULATE_WRITE, Linux 5.14), the
// same pages take half the time. Large pages (MADV_HUGEPAGE) would map them faster still, but
// there they make every later detection 10-15% slower and uneven, so they are not asked for.
// Only speed depends on it: where the kernel refuses, the first writes map the pages.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "core/tuning.hpp"

namespace smb::detail {

/// std::allocator, but a block of at least tuning::mapped_at_once_from bytes has its whole pages
/// mapped, writable, before it is handed out. The blocks themselves come from std::allocator, so
/// that the heap hands back memory it holds already (mapped) exactly as it would to a vector.
template <class T>
struct MappedAllocator {
    using value_type = T;

    static constexpr std::uintptr_t kPage = 4096;

    MappedAllocator() noexcept = default;
    template <class U>
    MappedAllocator(const MappedAllocator<U>& /*other*/) noexcept {}  // NOLINT: rebinding converts

    [[nodiscard]] T* allocate(std::size_t n) {
        T* block = std::allocator<T>().allocate(n);
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
        const std::size_t bytes = n * sizeof(T);
        if (bytes >= tuning::mapped_at_once_from) {
            const auto begin = (reinterpret_cast<std::uintptr_t>(block) + kPage - 1) & ~(kPage - 1);
            const auto end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kPage - 1);
            // A refusal (an older kernel) leaves the pages to the first writes: nothing to do.
            // NOLINTNEXTLINE(performance-no-int-to-ptr): the page-aligned interior of the block
            (void)::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
        }
#endif
        return block;
    }

    void deallocate(T* block, std::size_t n) noexcept { std::allocator<T>().deallocate(block, n); }

    template <class U>
    friend bool operator==(const MappedAllocator& /*a*/, const MappedAllocator<U>& /*b*/) noexcept {
        return true;
    }
};

/// A vector whose block has its pages mapped at once when it is large (MappedAllocator).
template <class T>
using BulkVector = std::vector<T, MappedAllocator<T>>;

}  // namespace smb::detail
