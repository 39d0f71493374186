// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A point mass's vehicle description as BindVehicles would give it (three force actuators along
// the world axes), made by hand for the control-stage tests that run without a MuJoCo model.
#ifndef MJFORMATION_TESTS_RUNNER_POINT_MASS_INFO_HPP_
#define MJFORMATION_TESTS_RUNNER_POINT_MASS_INFO_HPP_

#include "mjformation/plugin.h"

namespace mjf::testing {

struct PointMassInfo {
  static constexpr double kMass = 1.5, kGravity = 9.81;
  mjfActuatorInfo actuators[3];
  mjfVehicleInfo info{};
  PointMassInfo() {
    for (int k = 0; k < 3; ++k) {
      actuators[k] = mjfActuatorInfo{};
      actuators[k].gear[k] = 1;
      actuators[k].ctrl_min = -100;
      actuators[k].ctrl_max = 100;
    }
    info.mass = kMass;
    info.inertia[0] = info.inertia[1] = info.inertia[2] = 0.01;
    info.gravity = kGravity;
    info.n_actuators = 3;
    info.actuators = actuators;
  }
  // info.actuators points into this object: a copy would point into the original.
  PointMassInfo(const PointMassInfo&) = delete;
  PointMassInfo& operator=(const PointMassInfo&) = delete;
};

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_RUNNER_POINT_MASS_INFO_HPP_
