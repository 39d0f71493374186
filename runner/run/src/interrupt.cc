// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/run/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace mjf::runner {
namespace {

// Lock-free, so reading and writing it in a signal handler is well defined.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

extern "C" void OnSignal(int signal) {
  int expected = 0;
  if (!g_signal.compare_exchange_strong(expected, signal) && signal == SIGINT) {
    // Second Ctrl-C: the user wants out now. _exit is async-signal-safe; nothing is flushed.
    _exit(128 + SIGINT);
  }
}

}  // namespace

void InstallInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // blocking writes resume; the loops poll the flag
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // A file over RLIMIT_FSIZE then fails its write with EFBIG (reported, run marked incomplete)
  // instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
}

bool InterruptRequested() { return g_signal.load(std::memory_order_relaxed) != 0; }
int InterruptSignal() { return g_signal.load(std::memory_order_relaxed); }
void RequestInterrupt(int signal) { g_signal.store(signal, std::memory_order_relaxed); }
void ClearInterrupt() { g_signal.store(0, std::memory_order_relaxed); }
int InterruptExitCode() {
  const int s = InterruptSignal();
  return s ? 128 + s : 0;
}

}  // namespace mjf::runner
