// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/wrench_allocation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace mjf::runner {

WrenchAllocation::WrenchAllocation(const mjfVehicleInfo& info) {
  if (info.n_actuators != kActuators || !info.actuators) {
    throw std::invalid_argument(std::to_string(info.n_actuators) +
                                " actuators, not four rotors or a thrust and three moments");
  }
  Eigen::Matrix4d b;
  for (int k = 0; k < kActuators; ++k) {
    const mjfActuatorInfo& a = info.actuators[k];
    // Column k: actuator k's force along body z and its torque about the centre of mass,
    // site x force plus the gear's own torque (the rotor frame is the body frame).
    const Eigen::Vector3d pos(a.site_pos[0], a.site_pos[1], a.site_pos[2]);
    const Eigen::Vector3d force(a.gear[0], a.gear[1], a.gear[2]);
    const Eigen::Vector3d torque =
        pos.cross(force) + Eigen::Vector3d(a.gear[3], a.gear[4], a.gear[5]);
    b.col(k) << force.z(), torque;
    lo_[k] = a.ctrl_min;
    hi_[k] = a.ctrl_max;
  }
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(b);
  if (!lu.isInvertible()) {
    throw std::invalid_argument(
        "the actuators' allocation (thrust, moments vs controls) is singular");
  }
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(b_.data()) = b;
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(inverse_.data()) = lu.inverse();
}

void WrenchAllocation::Controls(const double wrench[4], double controls[4]) const {
  for (int k = 0; k < kActuators; ++k) {
    double u = 0;
    for (int j = 0; j < kActuators; ++j) u += inverse_[4 * k + j] * wrench[j];
    controls[k] = std::clamp(u, lo_[k], hi_[k]);
  }
}

void WrenchAllocation::Bounds(double low[4], double high[4]) const {
  for (int j = 0; j < kActuators; ++j) {
    low[j] = high[j] = 0;
    for (int k = 0; k < kActuators; ++k) {
      // An actuator without effect on this component adds nothing, even when its range is
      // unlimited (0 x inf would be NaN).
      if (b_[4 * j + k] == 0) continue;
      const double a = b_[4 * j + k] * lo_[k], c = b_[4 * j + k] * hi_[k];
      low[j] += std::min(a, c);
      high[j] += std::max(a, c);
    }
  }
}

}  // namespace mjf::runner
