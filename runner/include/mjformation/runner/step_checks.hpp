// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The checks after every physics step (single model and each partition alike): a MuJoCo warning
// or a non-finite state ends the run (docs/ARCHITECTURE.md, "Failure contract").
#ifndef MJFORMATION_RUNNER_STEP_CHECKS_HPP_
#define MJFORMATION_RUNNER_STEP_CHECKS_HPP_

#include <mujoco/mujoco.h>

namespace mjf::runner {

// Throws SimulationError naming the warning or the first non-finite qpos / qvel entry, at
// `time` (s). `qpos_offset` / `qvel_offset`: where `m`'s state starts in the whole swarm's
// (a partition's), so the index named is the whole model's.
void CheckStepState(const mjModel* m, const mjData* d, double time, int qpos_offset = 0,
                    int qvel_offset = 0);

}  // namespace mjf::runner

#endif  // MJFORMATION_RUNNER_STEP_CHECKS_HPP_
