// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/mujoco_errors.hpp"

#include <mujoco/mujoco.h>

#include <mutex>

namespace mjf::runner {
namespace {

thread_local std::string t_last_warning;

// MuJoCo 2.2.2 is C, compiled with unwind tables (x86-64 and arm64 ABIs), so a C++ exception
// thrown here unwinds through its frames back into the runner's step loop. The mjData that
// raised it is left mid-step; the run ends and no further step is taken on it.
void OnMujocoError(const char* message) {
  throw MujocoError(std::string("MuJoCo error: ") + message);
}

void OnMujocoWarning(const char* message) { t_last_warning = message; }

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = OnMujocoError;
    mju_user_warning = OnMujocoWarning;
  });
}

std::string LastMujocoWarning() { return t_last_warning; }
void ClearMujocoWarning() { t_last_warning.clear(); }

}  // namespace mjf::runner
