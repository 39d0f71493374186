// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/mujoco_errors.hpp"

#include <mujoco/mujoco.h>

#include <mutex>

namespace mjf::runner {
namespace {

thread_local std::string t_last_warning;

// MuJoCo is built with unwind tables (x86-64 and arm64 ABIs, and its own C++ parts), so a C++
// exception thrown here unwinds through its frames back into the runner's step loop. The mjData
// that raised it is left mid-step; the run ends and no further step is taken on it. MuJoCo's one
// log handler (mju_setLogHandler): an error must not return to the engine, so it unwinds to the
// caller as a MujocoError on the thread that raised it; a warning is kept for that thread's step
// checks; informational messages (opt-in timing topics) are not ours to show.
void OnMujocoLog(const mjLogMessage* message) {
  if (message->level == mjLOG_ERROR) {
    throw MujocoError(std::string("MuJoCo error: ") + message->subject);
  }
  if (message->level == mjLOG_WARNING) t_last_warning = message->subject;
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] { mju_setLogHandler(OnMujocoLog); });
}

std::string LastMujocoWarning() { return t_last_warning; }
void ClearMujocoWarning() { t_last_warning.clear(); }

}  // namespace mjf::runner
