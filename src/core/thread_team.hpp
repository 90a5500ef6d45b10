// SPDX-License-Identifier: MIT
#pragma once
// The threads a detection runs on (DetectionSettings::threads), and what each keeps for itself.
// Without OpenMP every pass runs on the calling thread, as thread 0 of a team of one.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "smb/settings.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace smb::detail {

/// DetectionSettings::threads (0: as many as OpenMP offers; 1 without OpenMP); the calling
/// thread's number in the parallel region under way and the number of threads in it (0 and 1
/// outside one, or without OpenMP).
#ifdef _OPENMP
[[nodiscard]] inline int thread_count(const DetectionSettings& settings) noexcept {
    return std::max(1, settings.threads == 0 ? omp_get_max_threads() : static_cast<int>(settings.threads));
}
[[nodiscard]] inline int this_thread() noexcept { return omp_get_thread_num(); }
[[nodiscard]] inline int team_size() noexcept { return omp_get_num_threads(); }
#else
[[nodiscard]] inline int thread_count(const DetectionSettings&) noexcept { return 1; }
[[nodiscard]] inline int this_thread() noexcept { return 0; }
[[nodiscard]] inline int team_size() noexcept { return 1; }
#endif

/// One T per thread, each on cache lines of its own: the threads write their own scratch and
/// counts all through a pass, and two of them sharing a line would pass it back and forth.
template <class T>
class PerThread {
    struct alignas(64) Own : T {};

public:
    /// One T for each of `threads` threads; those kept keep their buffers.
    void resize(int threads) {
        if (items_.size() != static_cast<std::size_t>(threads)) items_.resize(static_cast<std::size_t>(threads));
    }

    [[nodiscard]] std::size_t size() const noexcept { return items_.size(); }
    [[nodiscard]] T& operator[](std::size_t thread) noexcept { return items_[thread]; }
    [[nodiscard]] const T& operator[](std::size_t thread) const noexcept { return items_[thread]; }
    /// The calling thread's own, in a parallel region (this_thread()).
    [[nodiscard]] T& mine() noexcept { return items_[static_cast<std::size_t>(this_thread())]; }

    [[nodiscard]] auto begin() noexcept { return items_.begin(); }
    [[nodiscard]] auto end() noexcept { return items_.end(); }
    [[nodiscard]] auto begin() const noexcept { return items_.begin(); }
    [[nodiscard]] auto end() const noexcept { return items_.end(); }

    /// The bytes of the Ts themselves, and what bytes_of(t) says each holds besides.
    template <class BytesOf>
    [[nodiscard]] std::size_t bytes_held(BytesOf&& bytes_of) const {
        std::size_t bytes = items_.capacity() * sizeof(Own);
        for (const T& item : items_) bytes += bytes_of(item);
        return bytes;
    }

private:
    std::vector<Own> items_;
};

}  // namespace smb::detail
