// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A vehicle's actuator allocation: the wrench [collective thrust along body z (N), body moments
// about x, y, z (N m)] a set of four actuator controls gives, w = B u, and back,
// u = clamp(B^-1 w) within each actuator's ctrlrange. B is built from the actuator info the
// attitude plugins receive (site positions, gears, ranges), as the torque-authority check and
// the stock mixer build it; it covers rotors and thrust-and-moment actuators alike (for the
// latter B is diagonal). What the Python module's thrust-and-moment actions fly when they
// bypass the attitude plugins (docs/PYTHON.md). Plain arrays, no MuJoCo.
#ifndef MJFORMATION_CONTROL_WRENCH_ALLOCATION_HPP_
#define MJFORMATION_CONTROL_WRENCH_ALLOCATION_HPP_

#include <mjformation/plugin.h>

#include <array>

namespace mjf::runner {

class WrenchAllocation {
 public:
  static constexpr int kActuators = 4;
  // Throws std::invalid_argument saying why: not four actuators, or B singular.
  explicit WrenchAllocation(const mjfVehicleInfo& info);

  // controls[k] = (B^-1 wrench)_k clamped into actuator k's ctrlrange.
  void Controls(const double wrench[4], double controls[4]) const;
  // The range of each wrench component over the controls' box (each component alone, the
  // others free): low[j] = sum_k min(B_jk lo_k, B_jk hi_k), high[j] likewise with max.
  void Bounds(double low[4], double high[4]) const;

 private:
  std::array<double, 16> b_{};        // row-major: b_[4 * j + k] = B_jk
  std::array<double, 16> inverse_{};  // row-major B^-1
  std::array<double, 4> lo_{}, hi_{};
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_WRENCH_ALLOCATION_HPP_
