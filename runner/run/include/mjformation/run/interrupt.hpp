// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// SIGINT / SIGTERM / SIGHUP as a polled flag. The handler only stores the signal number in a
// lock-free atomic (async-signal-safe); long loops (a run's steps, a sweep's queue) poll
// InterruptRequested() and end cleanly: summary.json / sweep.csv written, marked incomplete.
// A second SIGINT while the first is being handled ends the process at once (exit 130), but only
// once the first was seen (InterruptRequested returned true) and 50 ms or more after it: a
// duplicate delivered in the same instant (`timeout -s INT` signals the process and its group)
// keeps the clean stop and its summary.
#ifndef MJFORMATION_RUN_INTERRUPT_HPP_
#define MJFORMATION_RUN_INTERRUPT_HPP_

namespace mjf::runner {

// Installs the handlers for SIGINT, SIGTERM and SIGHUP (idempotent). Called by the CLI, not by
// tests that do not want it.
void InstallInterruptHandlers();
// True once SIGINT, SIGTERM or SIGHUP arrived (or RequestInterrupt was called). Returning true
// marks the signal as seen: from then on a second SIGINT ends the process at once.
bool InterruptRequested();
// The signal that arrived (SIGINT, SIGTERM or SIGHUP), 0 if none.
int InterruptSignal();
// For tests and for code that wants the same clean stop: behaves as if `signal` arrived.
void RequestInterrupt(int signal);
// Clears the flag (tests).
void ClearInterrupt();
// The conventional exit code of a run ended by the signal: 128 + signal (130, 143, 129).
int InterruptExitCode();

}  // namespace mjf::runner

#endif  // MJFORMATION_RUN_INTERRUPT_HPP_
