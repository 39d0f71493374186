// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The four actuators of a vehicle as one linear map from controls to (thrust, moments): what the
// wrench allocation inverts and the torque authority measures.
#ifndef MJFORMATION_CONTROL_SRC_ACTUATOR_MATRIX_HPP_
#define MJFORMATION_CONTROL_SRC_ACTUATOR_MATRIX_HPP_

#include <mjformation/plugin.h>

#include <Eigen/Dense>

namespace mjf::runner {

struct ActuatorMatrix {
  Eigen::Matrix4d b;       // (thrust along body z, moments about body x, y, z) per unit control
  Eigen::Vector4d lo, hi;  // the controls' ranges
};

// Column k: actuator k's force along body z and its torque about the centre of mass, site x
// force plus the gear's own torque (the rotor frame is the body frame). `info` holds four
// actuators.
inline ActuatorMatrix ActuatorMatrixOf(const mjfVehicleInfo& info) {
  ActuatorMatrix m;
  for (int k = 0; k < 4; ++k) {
    const mjfActuatorInfo& a = info.actuators[k];
    const Eigen::Vector3d pos(a.site_pos[0], a.site_pos[1], a.site_pos[2]);
    const Eigen::Vector3d force(a.gear[0], a.gear[1], a.gear[2]);
    const Eigen::Vector3d torque =
        pos.cross(force) + Eigen::Vector3d(a.gear[3], a.gear[4], a.gear[5]);
    m.b.col(k) << force.z(), torque;
    m.lo[k] = a.ctrl_min;
    m.hi[k] = a.ctrl_max;
  }
  return m;
}

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_SRC_ACTUATOR_MATRIX_HPP_
