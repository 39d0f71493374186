// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/attitude/pointmass_direct.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mjf::attitude {

PointMassDirect::PointMassDirect(const Gains& gains, double mass, double gravity)
    : gains_(gains), mass_(mass), gravity_(gravity) {
  if (!(mass > 0) || !std::isfinite(mass)) {
    throw std::invalid_argument("vehicle mass must be positive (got " + std::to_string(mass) + ")");
  }
  if (!(gravity > 0) || !std::isfinite(gravity)) {
    throw std::invalid_argument("gravity must be positive (got " + std::to_string(gravity) + ")");
  }
  if (!(gains.kp_z >= 0) || !(gains.kd_z >= 0)) {
    throw std::invalid_argument("kp_z and kd_z must be >= 0");
  }
}

Vec3 PointMassDirect::Update(const VehicleState& state, const Setpoint& setpoint) const {
  return {mass_ * setpoint.acc[0], mass_ * setpoint.acc[1],
          mass_ * (gravity_ + setpoint.acc[2] + gains_.kp_z * (setpoint.pos[2] - state.pos[2]) +
                   gains_.kd_z * (setpoint.vel[2] - state.vel[2]))};
}

}  // namespace mjf::attitude
