// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/run/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdint>
#include <ctime>

namespace mjf::runner {
namespace {

// Lock-free, so reading and writing it in a signal handler is well defined.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

// Set once the program has noticed the first signal (InterruptRequested returned true), with
// the monotonic time the first signal arrived. A second SIGINT ends the process at once only
// when it comes after the first was seen and at least kDuplicateWindowNs later: `timeout -s
// INT` (and a terminal's Ctrl-C in some shells) delivers the same interrupt twice in the same
// instant, to the process and to its group, and that must not cost the user the summary.
std::atomic<bool> g_seen{false};
std::atomic<int64_t> g_first_ns{0};
constexpr int64_t kDuplicateWindowNs = 50'000'000;  // 50 ms: far below a human double tap
static_assert(std::atomic<int64_t>::is_always_lock_free, "the signal time must be lock-free");

int64_t MonotonicNs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe (POSIX.1-2008)
  return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

extern "C" void OnSignal(int signal) {
  int expected = 0;
  const int64_t now = MonotonicNs();
  if (g_signal.compare_exchange_strong(expected, signal)) {
    g_first_ns.store(now, std::memory_order_relaxed);
    return;
  }
  if (signal == SIGINT && g_seen.load(std::memory_order_relaxed) &&
      now - g_first_ns.load(std::memory_order_relaxed) >= kDuplicateWindowNs) {
    // A second Ctrl-C: the user wants out now. _exit is async-signal-safe; nothing is flushed.
    _exit(128 + SIGINT);
  }
  // Otherwise a duplicate of the first (or a SIGTERM / SIGHUP after it): the clean stop goes on.
}

}  // namespace

void InstallInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // blocking writes resume; the loops poll the flag
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // A closed terminal or a dropped ssh session: the same clean stop, the rows kept.
  sigaction(SIGHUP, &action, nullptr);
  // A file over RLIMIT_FSIZE then fails its write with EFBIG (reported, run marked incomplete)
  // instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
}

bool InterruptRequested() {
  const bool requested = g_signal.load(std::memory_order_relaxed) != 0;
  if (requested) g_seen.store(true, std::memory_order_relaxed);
  return requested;
}
int InterruptSignal() { return g_signal.load(std::memory_order_relaxed); }
void RequestInterrupt(int signal) { g_signal.store(signal, std::memory_order_relaxed); }
void ClearInterrupt() {
  g_signal.store(0, std::memory_order_relaxed);
  g_seen.store(false, std::memory_order_relaxed);
}
int InterruptExitCode() {
  const int s = InterruptSignal();
  return s ? 128 + s : 0;
}

}  // namespace mjf::runner
