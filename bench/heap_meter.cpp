// SPDX-License-Identifier: MIT
#include "heap_meter.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>

#if SMB_BENCH_HEAP_METER

extern "C" {
void* __libc_malloc(std::size_t size);
void __libc_free(void* block);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* block, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
}

namespace {

std::atomic<bool> counting{false};
std::atomic<std::int64_t> live{0};
std::atomic<std::int64_t> peak{0};

void note_allocated(void* block) noexcept {
    if (block == nullptr || !counting.load(std::memory_order_relaxed)) return;
    const auto size = static_cast<std::int64_t>(malloc_usable_size(block));
    const auto now = live.fetch_add(size, std::memory_order_relaxed) + size;
    std::int64_t highest = peak.load(std::memory_order_relaxed);
    while (now > highest && !peak.compare_exchange_weak(highest, now, std::memory_order_relaxed)) {}
}

void note_freed(void* block) noexcept {
    if (block == nullptr || !counting.load(std::memory_order_relaxed)) return;
    live.fetch_sub(static_cast<std::int64_t>(malloc_usable_size(block)), std::memory_order_relaxed);
}

void* aligned_block(std::size_t alignment, std::size_t size) noexcept {
    void* block = __libc_memalign(alignment, size);
    note_allocated(block);
    return block;
}

}  // namespace

extern "C" {

void* malloc(std::size_t size) {
    void* block = __libc_malloc(size);
    note_allocated(block);
    return block;
}

void free(void* block) {
    note_freed(block);
    __libc_free(block);
}

void* calloc(std::size_t count, std::size_t size) {
    void* block = __libc_calloc(count, size);
    note_allocated(block);
    return block;
}

void* realloc(void* block, std::size_t size) {
    const std::size_t old_size = block != nullptr ? malloc_usable_size(block) : 0;
    void* moved = __libc_realloc(block, size);
    if (moved != nullptr || size == 0) {
        if (counting.load(std::memory_order_relaxed))
            live.fetch_sub(static_cast<std::int64_t>(old_size), std::memory_order_relaxed);
        note_allocated(moved);
    }
    return moved;
}

void* memalign(std::size_t alignment, std::size_t size) { return aligned_block(alignment, size); }
void* aligned_alloc(std::size_t alignment, std::size_t size) { return aligned_block(alignment, size); }
void* valloc(std::size_t size) { return aligned_block(static_cast<std::size_t>(sysconf(_SC_PAGESIZE)), size); }

void* pvalloc(std::size_t size) {
    const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    return aligned_block(page, (size + page - 1) / page * page);
}

int posix_memalign(void** result, std::size_t alignment, std::size_t size) {
    if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return EINVAL;
    void* block = aligned_block(alignment, size);
    if (block == nullptr && size != 0) return ENOMEM;
    *result = block;
    return 0;
}

}  // extern "C"

namespace smb::bench::heap_meter {

bool available() noexcept { return true; }
void set_counting(bool on) noexcept { counting.store(on, std::memory_order_relaxed); }
std::size_t live_bytes() noexcept { return static_cast<std::size_t>(std::max<std::int64_t>(0, live.load())); }
std::size_t peak_bytes() noexcept { return static_cast<std::size_t>(peak.load()); }

}  // namespace smb::bench::heap_meter

#else

namespace smb::bench::heap_meter {

bool available() noexcept { return false; }
void set_counting(bool) noexcept {}
std::size_t live_bytes() noexcept { return 0; }
std::size_t peak_bytes() noexcept { return 0; }

}  // namespace smb::bench::heap_meter

#endif
