// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Aerodynamic force on a multirotor from its velocity relative to the air, world frame:
//   F_xy = -(k_rotor + 1/2 rho CdA_h |v_r|) v_r,xy      (rotor drag + body drag, horizontal)
//   F_z  = -(1/2 rho CdA_v |v_r|) v_r,z                 (body drag, vertical)
// with v_r = v_vehicle - v_wind. Rotor drag (blade flapping / induced drag, linear in the
// airspeed across the disc) dominates at low speed; bluff-body drag grows with its square.
// Attitude is neglected (the vehicles stay within ~20 deg of level; docs/REALISM.md).
#ifndef MJFORMATION_REALISM_DRAG_HPP_
#define MJFORMATION_REALISM_DRAG_HPP_

#include <array>

namespace mjf::realism {

struct DragParams {
  double rotor_linear = 0.0;    // k_rotor, N s/m, horizontal
  double cda_horizontal = 0.0;  // Cd * frontal area, m^2
  double cda_vertical = 0.0;    // Cd * top area, m^2
  double air_density = 1.225;   // rho, kg/m^3 (ISA sea level)

  // The Iris-like quadrotor of mjcf/quadrotor.xml; derivation in drag.cc.
  static DragParams Iris();

  // Force (N, world frame) on a vehicle moving at `velocity` through air moving at `wind` (m/s).
  std::array<double, 3> Force(const double velocity[3], const double wind[3]) const;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_DRAG_HPP_
