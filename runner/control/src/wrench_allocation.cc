// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/wrench_allocation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "actuator_matrix.hpp"

namespace mjf::runner {

WrenchAllocation::WrenchAllocation(const mjfVehicleInfo& info) {
  if (info.n_actuators != kActuators || !info.actuators) {
    throw std::invalid_argument(std::to_string(info.n_actuators) +
                                " actuators, not four rotors or a thrust and three moments");
  }
  const ActuatorMatrix m = ActuatorMatrixOf(info);
  const Eigen::Matrix4d& b = m.b;
  Eigen::Map<Eigen::Vector4d>(lo_.data()) = m.lo;
  Eigen::Map<Eigen::Vector4d>(hi_.data()) = m.hi;
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
