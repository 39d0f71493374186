// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The checks after every physics step (single model and each partition alike): a MuJoCo warning
// or a non-finite state ends the run (docs/ARCHITECTURE.md, "Failure contract").
#ifndef MJFORMATION_SIM_STEP_CHECKS_HPP_
#define MJFORMATION_SIM_STEP_CHECKS_HPP_

#include <mujoco/mujoco.h>

namespace mjf::runner {

// Where a partition's state starts in the whole swarm's model, so that the indices named in
// messages (MuJoCo's warning text included) are the whole model's.
struct StateOffsets {
  int qpos = 0, dof = 0, actuator = 0;
};

// Throws SimulationError naming the warning or the first non-finite qpos / qvel entry, at
// `time` (s).
void CheckStepState(const mjModel* m, const mjData* d, double time, StateOffsets offsets = {});

}  // namespace mjf::runner

#endif  // MJFORMATION_SIM_STEP_CHECKS_HPP_
