// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/control/src/wrench_allocation.cc: a wanted thrust and body moments turned into the
// controls of an X rotor layout and of a thrust-and-moment vehicle, clamped into the ranges,
// and the wrench bounds over the ranges; layouts it cannot invert are refused saying why.
#include "mjformation/control/wrench_allocation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <stdexcept>
#include <vector>

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

mjfActuatorInfo Actuator(const std::array<double, 3>& pos, const std::array<double, 6>& gear,
                         double lo, double hi) {
  mjfActuatorInfo a{};
  for (int i = 0; i < 3; ++i) a.site_pos[i] = pos[i];
  for (int i = 0; i < 6; ++i) a.gear[i] = gear[i];
  a.ctrl_min = lo;
  a.ctrl_max = hi;
  return a;
}

mjfVehicleInfo Vehicle(const std::vector<mjfActuatorInfo>& actuators) {
  mjfVehicleInfo v{};
  v.mass = 1.5;
  v.gravity = 9.81;
  v.n_actuators = static_cast<int>(actuators.size());
  v.actuators = actuators.data();
  return v;
}

// An X quadrotor: arm d on the diagonals, yaw gear +-c, rotors in [0, 7] N.
constexpr double kD = 0.18, kC = 0.016, kMax = 7.0;
std::vector<mjfActuatorInfo> XRotors() {
  return {Actuator({kD, -kD, 0}, {0, 0, 1, 0, 0, -kC}, 0, kMax),
          Actuator({-kD, -kD, 0}, {0, 0, 1, 0, 0, kC}, 0, kMax),
          Actuator({-kD, kD, 0}, {0, 0, 1, 0, 0, -kC}, 0, kMax),
          Actuator({kD, kD, 0}, {0, 0, 1, 0, 0, kC}, 0, kMax)};
}

TEST(WrenchAllocation, ThrustAloneIsSharedEquallyByTheRotors) {
  const auto rotors = XRotors();
  const WrenchAllocation allocation(Vehicle(rotors));
  const double wrench[4] = {14.715, 0, 0, 0};
  double u[4];
  allocation.Controls(wrench, u);
  for (double c : u) EXPECT_NEAR(c, 14.715 / 4, 1e-12);
}

TEST(WrenchAllocation, AMomentSpeedsUpTheRotorsOnItsSide) {
  const auto rotors = XRotors();
  const WrenchAllocation allocation(Vehicle(rotors));
  // Roll +0.36 N m = d (u2 + u3 - u0 - u1): the rotors at y > 0 (2, 3) push 1 N more than
  // those at y < 0 (0, 1); the yaw gears cancel pairwise.
  const double wrench[4] = {12, 0.36, 0, 0};
  double u[4];
  allocation.Controls(wrench, u);
  EXPECT_NEAR(u[0], 2.5, 1e-12);
  EXPECT_NEAR(u[1], 2.5, 1e-12);
  EXPECT_NEAR(u[2], 3.5, 1e-12);
  EXPECT_NEAR(u[3], 3.5, 1e-12);
}

TEST(WrenchAllocation, ControlsAreClampedIntoTheirRanges) {
  const auto rotors = XRotors();
  const WrenchAllocation allocation(Vehicle(rotors));
  const double too_much[4] = {100, 0, 0, 0}, negative[4] = {-5, 0, 0, 0};
  double u[4];
  allocation.Controls(too_much, u);
  for (double c : u) EXPECT_EQ(c, kMax);
  allocation.Controls(negative, u);
  for (double c : u) EXPECT_EQ(c, 0.0);
}

TEST(WrenchAllocation, BoundsAreEachComponentsRangeOverTheControls) {
  const auto rotors = XRotors();
  const WrenchAllocation allocation(Vehicle(rotors));
  double low[4], high[4];
  allocation.Bounds(low, high);
  EXPECT_NEAR(low[0], 0, 1e-12);
  EXPECT_NEAR(high[0], 4 * kMax, 1e-12);
  EXPECT_NEAR(high[1], 2 * kD * kMax, 1e-12);  // two rotors at full thrust on one side
  EXPECT_NEAR(low[1], -2 * kD * kMax, 1e-12);
  EXPECT_NEAR(high[3], 2 * kC * kMax, 1e-12);
}

TEST(WrenchAllocation, ThrustAndMomentActuatorsAreDividedByTheirGears) {
  const std::vector<mjfActuatorInfo> actuators = {Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0}, 0, 0.35),
                                                  Actuator({0, 0, 0}, {0, 0, 0, -1, 0, 0}, -1, 1),
                                                  Actuator({0, 0, 0}, {0, 0, 0, 0, -2, 0}, -1, 1),
                                                  Actuator({0, 0, 0}, {0, 0, 0, 0, 0, -1}, -1, 1)};
  const WrenchAllocation allocation(Vehicle(actuators));
  const double wrench[4] = {0.2, 0.1, 0.4, -0.3};
  double u[4];
  allocation.Controls(wrench, u);
  EXPECT_DOUBLE_EQ(u[0], 0.2);
  EXPECT_DOUBLE_EQ(u[1], -0.1);
  EXPECT_DOUBLE_EQ(u[2], -0.2);
  EXPECT_DOUBLE_EQ(u[3], 0.3);
}

TEST(WrenchAllocation, AnUnlimitedRangeBoundsOnlyWhatItActsOn) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<mjfActuatorInfo> actuators = {
      Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0}, 0, 0.35),
      Actuator({0, 0, 0}, {0, 0, 0, 1, 0, 0}, -inf, inf),
      Actuator({0, 0, 0}, {0, 0, 0, 0, 1, 0}, -1, 1),
      Actuator({0, 0, 0}, {0, 0, 0, 0, 0, 1}, -1, 1)};
  const WrenchAllocation allocation(Vehicle(actuators));
  double low[4], high[4];
  allocation.Bounds(low, high);
  EXPECT_EQ(low[0], 0.0);
  EXPECT_EQ(high[0], 0.35);
  EXPECT_EQ(low[1], -inf);
  EXPECT_EQ(high[1], inf);
  EXPECT_EQ(high[2], 1.0);
}

TEST(WrenchAllocation, RefusesWhatItCannotInvert) {
  const std::vector<mjfActuatorInfo> three = {Actuator({0, 0, 0}, {1, 0, 0, 0, 0, 0}, -1, 1),
                                              Actuator({0, 0, 0}, {0, 1, 0, 0, 0, 0}, -1, 1),
                                              Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0}, -1, 1)};
  try {
    WrenchAllocation{Vehicle(three)};
    FAIL() << "a point mass's three forces were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("3 actuators"));
  }
  auto rotors = XRotors();
  for (auto& r : rotors) r.site_pos[0] = r.site_pos[1] = 0;  // every rotor on the centre
  EXPECT_THROW(WrenchAllocation{Vehicle(rotors)}, std::invalid_argument);
}

}  // namespace
}  // namespace mjf::runner
