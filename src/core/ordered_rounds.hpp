// SPDX-License-Identifier: MIT
#pragma once
// Work shared among threads whose results must reach the caller in order, on the calling
// thread: the cell checks of the persistent-cut pipeline (columns) and the skin list's pass
// over its candidates (blocks).

#include <atomic>
#include <cstddef>
#include <exception>
#include <vector>

#include "core/thread_team.hpp"

namespace smb::detail {

/// Runs work(item, buffer) for items 0..count-1 on `threads` threads, in rounds of `round` items,
/// and hand_on(item, buffer) in item order on the calling thread, one round behind (while the
/// threads work on round r, it hands round r - 1 on). Item i gets buffer i % (2 * round) of
/// `buffers` (grown if smaller), written again only after it was handed on. An exception of
/// hand_on (a caller's sink) skips what is left and is thrown again once the threads joined.
template <class Buffer, class Work, class HandOn>
void run_in_ordered_rounds(int threads, std::size_t count, std::size_t round, std::vector<Buffer>& buffers, Work&& work,
                           HandOn&& hand_on) {
    if (buffers.size() < 2 * round) buffers.resize(2 * round);
    auto buffer_of = [&](std::size_t item) -> Buffer& { return buffers[item % (2 * round)]; };
    const std::size_t rounds = (count + round - 1) / round;
    std::exception_ptr failure;
    std::atomic<bool> failed{false};
#pragma omp parallel num_threads(threads)
    {
        for (std::size_t r = 0; r <= rounds; ++r) {
#pragma omp master
            {
                if (r > 0 && !failed.load(std::memory_order_relaxed)) {
                    try {
                        for (std::size_t item = (r - 1) * round; item < count && item < r * round; ++item)
                            hand_on(item, buffer_of(item));
                    } catch (...) {
                        failure = std::current_exception();
                        failed.store(true, std::memory_order_relaxed);
                    }
                }
            }
            if (r < rounds) {
                const std::size_t first = r * round;
                const auto in_round = static_cast<std::ptrdiff_t>(count - first < round ? count - first : round);
                // The barrier at the end of this loop also waits for the hand-over above, so the
                // next round never writes into buffers that are still being handed on.
#pragma omp for schedule(dynamic, 1)
                for (std::ptrdiff_t b = 0; b < in_round; ++b) {
                    if (failed.load(std::memory_order_relaxed)) continue;
                    const std::size_t item = first + static_cast<std::size_t>(b);
                    work(item, buffer_of(item));
                }
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace smb::detail
