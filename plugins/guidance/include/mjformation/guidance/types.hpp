// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What every guidance law of one vehicle shares (no MuJoCo, no plugin ABI): the command it
// writes on the setpoint bus and the PD gains of the laws that track a reference.
#ifndef MJFORMATION_GUIDANCE_TYPES_HPP_
#define MJFORMATION_GUIDANCE_TYPES_HPP_

#include <array>

namespace mjf::guidance {

using Vec3 = std::array<double, 3>;

// What a guidance law writes on the setpoint bus (mjfSetpoint without the sliding diagnostics).
struct GuidanceOutput {
  Vec3 acc{};      // m/s^2, world: x, y command (feedforward + feedback); z feedforward
  Vec3 pos{};      // m, reference position (z: altitude setpoint)
  Vec3 vel{};      // m/s, reference velocity
  double yaw = 0;  // rad
};

struct TrackingGains {
  double kp = 1;  // 1/s^2, position error -> acceleration
  double kd =
      2;  // 1/s, velocity error -> acceleration (kp = 1, kd = 2: critically damped, 1 rad/s)
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_TYPES_HPP_
