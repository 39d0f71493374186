// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
// The horizontal acceleration bound the host gives accel_limit = "vehicle", from plain vehicle
// descriptions (no MuJoCo): tilt-limited rotorcraft, direct-force point mass, refusals.
#include "mjformation/control/vehicle_accel_limit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace mjf::runner {
namespace {

constexpr double kG = 9.81;

mjfActuatorInfo Actuator(double gx, double gy, double gz, double lo, double hi) {
  mjfActuatorInfo a{};
  a.gear[0] = gx;
  a.gear[1] = gy;
  a.gear[2] = gz;
  a.ctrl_min = lo;
  a.ctrl_max = hi;
  return a;
}

mjfVehicleInfo Vehicle(double mass, const std::vector<mjfActuatorInfo>& actuators) {
  mjfVehicleInfo v{};
  v.mass = mass;
  v.gravity = kG;
  v.n_actuators = static_cast<int>(actuators.size());
  v.actuators = actuators.data();
  return v;
}

TEST(VehicleAccelLimit, TiltBindsWhenThrustIsAmple) {
  // Four rotors of 10 N each on 1.5 kg: thrust/weight 2.72, spare g sqrt(2.72^2 - 1) = 24.8.
  const std::vector<mjfActuatorInfo> rotors(4, Actuator(0, 0, 1, 0, 10));
  std::string why;
  EXPECT_NEAR(VehicleAccelBound(Vehicle(1.5, rotors), true, 0.35, &why), kG * std::tan(0.35),
              1e-12);
}

TEST(VehicleAccelLimit, SpareThrustBindsWhenTiltIsLarge) {
  // Thrust/weight 1.2: what is left after holding altitude is g sqrt(1.44 - 1) < g tan(1.2).
  const double mass = 1.0, thrust = 1.2 * mass * kG;
  const std::vector<mjfActuatorInfo> rotors(2, Actuator(0, 0, 1, 0, thrust / 2));
  std::string why;
  EXPECT_NEAR(VehicleAccelBound(Vehicle(mass, rotors), true, 1.2, &why),
              kG * std::sqrt(1.2 * 1.2 - 1.0), 1e-9);
}

TEST(VehicleAccelLimit, PointMassUsesTheSmallerHorizontalRange) {
  // x pushes 4 N either way, y 3 N forward and 6 N back: the disc inside is 3 N / 2 kg. The
  // point mass's actuators drive slide joints, whose gain is gear[0] whatever the joint's axis.
  const std::vector<mjfActuatorInfo> force = {Actuator(1, 0, 0, -4, 4), Actuator(1, 0, 0, -6, 3),
                                              Actuator(0, 0, 1, -100, 100)};
  std::string why;
  EXPECT_DOUBLE_EQ(VehicleAccelBound(Vehicle(2.0, force), false, 0.0, &why), 1.5);
}

TEST(VehicleAccelLimit, RefusesVehiclesWithoutABound) {
  std::string why;
  const std::vector<mjfActuatorInfo> unlimited = {Actuator(1, 0, 0, -INFINITY, INFINITY),
                                                  Actuator(0, 1, 0, -INFINITY, INFINITY)};
  EXPECT_LT(VehicleAccelBound(Vehicle(1.0, unlimited), false, 0.0, &why), 0.0);
  EXPECT_NE(why.find("finite positive control range"), std::string::npos) << why;
  const std::vector<mjfActuatorInfo> weak(4, Actuator(0, 0, 1, 0, 1.0));  // 4 N for 9.81 N
  why.clear();
  EXPECT_LT(VehicleAccelBound(Vehicle(1.0, weak), true, 0.5, &why), 0.0);
  EXPECT_NE(why.find("cannot lift"), std::string::npos) << why;
  why.clear();
  EXPECT_LT(VehicleAccelBound(Vehicle(0.0, weak), true, 0.5, &why), 0.0);
  EXPECT_NE(why.find("no mass"), std::string::npos) << why;
  const std::vector<mjfActuatorInfo> one = {Actuator(1, 0, 0, -1, 1)};
  why.clear();
  EXPECT_LT(VehicleAccelBound(Vehicle(1.0, one), false, 0.0, &why), 0.0);
  EXPECT_NE(why.find("neither a tilt limit"), std::string::npos) << why;
}

}  // namespace
}  // namespace mjf::runner
