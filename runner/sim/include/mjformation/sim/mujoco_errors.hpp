// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// MuJoCo's error and warning callbacks (mju_user_error / mju_user_warning) are process-wide
// function pointers; by default an engine error prints and exits the process and a warning
// appends to MUJOCO_LOG.TXT in the working directory. The runner installs its own once:
// - an engine error throws MujocoError on the thread that raised it, so it ends the simulation
//   running on that thread (several run on threads of one process) and no other;
// - a warning is kept in a thread-local buffer (LastMujocoWarning) for the simulation on that
//   thread; nothing is ever written into the user's working directory.
#ifndef MJFORMATION_SIM_MUJOCO_ERRORS_HPP_
#define MJFORMATION_SIM_MUJOCO_ERRORS_HPP_

#include <string>

#include "mjformation/control/errors.hpp"

namespace mjf::runner {

class MujocoError : public SimulationError {
 public:
  using SimulationError::SimulationError;
};

// Installs the handlers (idempotent, thread-safe).
void InstallMujocoHandlers();
// The last MuJoCo warning text raised on this thread ("" if none) and a way to clear it.
std::string LastMujocoWarning();
void ClearMujocoWarning();

}  // namespace mjf::runner

#endif  // MJFORMATION_SIM_MUJOCO_ERRORS_HPP_
