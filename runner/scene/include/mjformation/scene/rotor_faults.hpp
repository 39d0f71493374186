// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// [[vehicles.fault]] bound to the vehicles' controls: from a fault's time on, the rotor's control
// becomes (1 - thrust_share) x its control clamped to the actuator's range. A function of the
// step's time alone (no state), so the runner's actuation (sim/actuation.hpp) and the native
// swarm plugin apply the same operations to the same controls and fly the same bits.
#ifndef MJFORMATION_SCENE_ROTOR_FAULTS_HPP_
#define MJFORMATION_SCENE_ROTOR_FAULTS_HPP_

#include <algorithm>
#include <cstddef>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::runner {

struct BoundRotorFault {
  size_t control = 0;  // index into the controls, [vehicle][actuator]
  double at = 0.0;     // s
  double keep = 1.0;   // 1 - thrust_share
  double ctrl_min = 0.0, ctrl_max = 0.0;
};

// The experiment's faults on the vehicles `bindings` holds (vehicle `first_vehicle` and on;
// 0 = leader). Throws ConfigError naming the fault's line for a rotor the vehicle does not have.
std::vector<BoundRotorFault> BindRotorFaults(const ExperimentConfig& config,
                                             const VehicleBindings& bindings, int first_vehicle);

// The faults in force at `time` (a step's time; half a step absorbs its rounding) applied to
// `controls` ([vehicle][actuator]).
inline void ApplyRotorFaults(const std::vector<BoundRotorFault>& faults, double time,
                             double timestep, double* controls) {
  for (const BoundRotorFault& f : faults) {
    if (time < f.at - 0.5 * timestep) continue;
    controls[f.control] = f.keep * std::clamp(controls[f.control], f.ctrl_min, f.ctrl_max);
  }
}

}  // namespace mjf::runner

#endif  // MJFORMATION_SCENE_ROTOR_FAULTS_HPP_
