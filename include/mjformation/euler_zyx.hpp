// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Euler angles of a quaternion, in the one convention the project uses: the runner records them
// (timeseries.csv) and the attitude plugins regulate them, so both read this one definition.
// Header-only and plain C++, like time_steps.hpp, so the runner and the plugins share it.
#ifndef MJFORMATION_EULER_ZYX_HPP_
#define MJFORMATION_EULER_ZYX_HPP_

#include <algorithm>
#include <array>
#include <cmath>

namespace mjf {

// Roll, pitch, yaw (rad) of a body -> world quaternion (w, x, y, z), ZYX convention:
// R = Rz(yaw) Ry(pitch) Rx(roll). Pitch is clamped into asin's domain, so a quaternion a
// rounding away from unit length at +-90 degrees gives +-pi/2, not NaN.
inline std::array<double, 3> EulerZYX(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y)),
          std::asin(std::clamp(2 * (w * y - z * x), -1.0, 1.0)),
          std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))};
}

}  // namespace mjf

#endif  // MJFORMATION_EULER_ZYX_HPP_
