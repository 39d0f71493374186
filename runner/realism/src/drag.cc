// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/drag.hpp"

#include <cmath>

namespace mjf::realism {

// Rotor drag: PX4 sitl_gazebo's Iris (models/iris/iris.sdf, gazebo_motor_model) applies per
// rotor F = -|omega| rotorDragCoefficient v_perp with rotorDragCoefficient = 8.06428e-5 N s/(m
// rad). At hover each rotor carries m g / 4 = 1.5 * 9.81 / 4 = 3.68 N = motorConstant omega^2 with
// motorConstant 5.84e-6 N s^2, so omega_hover = 794 rad/s and the four rotors give
// 4 * 794 * 8.06428e-5 = 0.256 N s/m (taken constant: omega stays near hover in these flights).
// Body drag: Cd = 1.0 (a bluff body; Hoerner, Fluid-Dynamic Drag, 1965, ch. 3) on the Iris
// collision box of iris.sdf, 0.47 x 0.47 x 0.11 m: frontal area 0.47 * 0.11 = 0.0517 m^2, top
// area 0.47 * 0.47 = 0.221 m^2.
DragParams DragParams::Iris() {
  DragParams p;
  const double omega_hover = std::sqrt(1.5 * 9.81 / 4 / 5.84e-6);
  p.rotor_linear = 4 * omega_hover * 8.06428e-5;
  p.cda_horizontal = 1.0 * 0.47 * 0.11;
  p.cda_vertical = 1.0 * 0.47 * 0.47;
  return p;
}

std::array<double, 3> DragParams::Force(const double velocity[3], const double wind[3]) const {
  const double r[3] = {velocity[0] - wind[0], velocity[1] - wind[1], velocity[2] - wind[2]};
  const double speed = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double horizontal = rotor_linear + 0.5 * air_density * cda_horizontal * speed;
  const double vertical = 0.5 * air_density * cda_vertical * speed;
  return {-horizontal * r[0], -horizontal * r[1], -vertical * r[2]};
}

}  // namespace mjf::realism
