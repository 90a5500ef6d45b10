// SPDX-License-Identifier: MIT
#include "partial_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

namespace smb::io {

namespace {

constexpr std::size_t kPathBytes = 4096;

/// A path the handlers may remove: `state` says whether `path` is complete and current.
struct PartialSlot {
    std::atomic<int> state{0};  // 0: free, 1: being filled, 2: holds a path
    std::array<char, kPathBytes> path{};
};

constexpr int kSlots = 16;
std::array<PartialSlot, kSlots> slots;
static_assert(std::atomic<int>::is_always_lock_free, "the signal handlers read the slots' states");

// The signals whose default action ends the program (SIGKILL cannot be caught; SIGPROF,
// SIGVTALRM and SIGTRAP belong to profilers and debuggers), then the faults.
constexpr std::array kCleanedSignals = {SIGINT,  SIGTERM, SIGHUP,  SIGPIPE, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM,
                                        SIGXCPU, SIGXFSZ, SIGABRT, SIGSYS,  SIGSEGV, SIGBUS,  SIGFPE,  SIGILL};
/// A fault ends the program whatever handles it (a sanitizer reports it and exits): the clean-up
/// runs first, then that handler.
bool is_fault(int signal) { return signal == SIGSEGV || signal == SIGBUS || signal == SIGFPE || signal == SIGILL; }
std::array<struct sigaction, kCleanedSignals.size()> previous_actions{};

void remove_partial_files() noexcept {
    for (PartialSlot& slot : slots) {
        if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path.data());
    }
}

void on_fatal_signal(int signal, siginfo_t* info, void*) {
    const int saved_errno = errno;
    remove_partial_files();
    for (std::size_t i = 0; i < kCleanedSignals.size(); ++i) {
        if (kCleanedSignals[i] == signal) ::sigaction(signal, &previous_actions[i], nullptr);
    }
    // A fault (SIGSEGV from a bad access, say) happens again when the handler returns, now
    // under the previous action, which then sees it as it was; a signal that was sent (kill,
    // raise, abort) is sent again, to be delivered under the previous action once this returns.
    const bool sent = info == nullptr || info->si_code <= 0;
    if (sent) ::raise(signal);
    errno = saved_errno;
}

void install_handlers() {
    for (std::size_t i = 0; i < kCleanedSignals.size(); ++i) {
        struct sigaction action {};
        action.sa_sigaction = on_fatal_signal;
        action.sa_flags = SA_SIGINFO;
        sigemptyset(&action.sa_mask);
        ::sigaction(kCleanedSignals[i], nullptr, &previous_actions[i]);
        // A signal the program ignores (SIGHUP under nohup, say) or handles and lives on stays
        // as it was.
        const bool by_default =
            (previous_actions[i].sa_flags & SA_SIGINFO) == 0 && previous_actions[i].sa_handler == SIG_DFL;
        if (by_default || is_fault(kCleanedSignals[i])) ::sigaction(kCleanedSignals[i], &action, nullptr);
    }
}

}  // namespace

int remember_partial_file(const std::string& path) {
    static std::once_flag installed;
    std::call_once(installed, install_handlers);
    if (path.size() >= kPathBytes) return -1;
    for (int i = 0; i < kSlots; ++i) {
        PartialSlot& slot = slots[static_cast<std::size_t>(i)];
        int expected = 0;
        if (!slot.state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) continue;
        std::memcpy(slot.path.data(), path.c_str(), path.size() + 1);
        slot.state.store(2, std::memory_order_release);
        return i;
    }
    return -1;
}

void forget_partial_file(int slot) noexcept {
    if (slot < 0 || slot >= kSlots) return;
    slots[static_cast<std::size_t>(slot)].state.store(0, std::memory_order_release);
}

}  // namespace smb::io
