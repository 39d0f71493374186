// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/control/src/torque_authority.cc: each axis' angular acceleration at hover from plain
// actuator descriptions (no MuJoCo), for a thrust-and-moment vehicle and an X rotor layout, and
// the warning when the attitude loop asks for more.
#include "mjformation/control/torque_authority.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mjf::runner {
namespace {

using ::testing::HasSubstr;

constexpr double kG = 9.81;

mjfActuatorInfo Actuator(const std::array<double, 3>& pos, const std::array<double, 6>& gear,
                         double lo, double hi) {
  mjfActuatorInfo a{};
  for (int i = 0; i < 3; ++i) a.site_pos[i] = pos[i];
  for (int i = 0; i < 6; ++i) a.gear[i] = gear[i];
  a.ctrl_min = lo;
  a.ctrl_max = hi;
  return a;
}

mjfVehicleInfo Vehicle(double mass, const std::array<double, 3>& inertia,
                       const std::vector<mjfActuatorInfo>& actuators) {
  mjfVehicleInfo v{};
  v.mass = mass;
  v.gravity = kG;
  for (int i = 0; i < 3; ++i) v.inertia[i] = inertia[i];
  v.n_actuators = static_cast<int>(actuators.size());
  v.actuators = actuators.data();
  return v;
}

// A cf2-like thrust and three moments with the moment gears negative: the authority is the
// range times |gear| over the inertia, whatever the sign.
std::vector<mjfActuatorInfo> ThrustMoments(double roll, double pitch, double yaw) {
  return {Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0}, 0, 0.35),
          Actuator({0, 0, 0}, {0, 0, 0, -1, 0, 0}, -roll, roll),
          Actuator({0, 0, 0}, {0, 0, 0, 0, -2, 0}, -pitch, pitch),
          Actuator({0, 0, 0}, {0, 0, 0, 0, 0, -1}, -yaw, yaw)};
}

TEST(TorqueAuthority, ThrustAndMomentsIsRangeTimesGearOverInertia) {
  const auto actuators = ThrustMoments(1e-5, 2e-5, 3e-5);
  const TorqueAuthority a = ComputeTorqueAuthority(Vehicle(0.027, {2.5e-5, 4e-5, 3e-5}, actuators));
  ASSERT_TRUE(a.known) << a.why;
  EXPECT_NEAR(a.torque[0], 1e-5, 1e-15);
  EXPECT_NEAR(a.torque[1], 4e-5, 1e-15);  // range 2e-5 x |gear| 2
  EXPECT_NEAR(a.torque[2], 3e-5, 1e-15);
  EXPECT_NEAR(a.accel[0], 0.4, 1e-12);
  EXPECT_NEAR(a.accel[1], 1.0, 1e-12);
  EXPECT_NEAR(a.accel[2], 1.0, 1e-12);
}

TEST(TorqueAuthority, RotorLayoutIsTheHoverMarginOnTheArms) {
  // An X layout, arms 0.2 m (x) and 0.1 m (y), 10 N rotors on 2 kg: hover takes 4.905 N each,
  // so +-4.905 N per rotor (the floor binds before the 10 N ceiling). Roll: four rotors on a
  // 0.1 m lever, 4 x 0.1 x 4.905 = 1.962 N m; pitch on 0.2 m: 3.924 N m; yaw: 4 x 0.05 x 4.905.
  const double c = 0.05;
  const std::vector<mjfActuatorInfo> rotors = {
      Actuator({0.2, -0.1, 0}, {0, 0, 1, 0, 0, -c}, 0, 10),
      Actuator({-0.2, 0.1, 0}, {0, 0, 1, 0, 0, -c}, 0, 10),
      Actuator({0.2, 0.1, 0}, {0, 0, 1, 0, 0, c}, 0, 10),
      Actuator({-0.2, -0.1, 0}, {0, 0, 1, 0, 0, c}, 0, 10)};
  const TorqueAuthority a = ComputeTorqueAuthority(Vehicle(2.0, {0.02, 0.04, 0.05}, rotors));
  ASSERT_TRUE(a.known) << a.why;
  const double margin = 2.0 * kG / 4;
  EXPECT_NEAR(a.torque[0], 4 * 0.1 * margin, 1e-12);
  EXPECT_NEAR(a.torque[1], 4 * 0.2 * margin, 1e-12);
  EXPECT_NEAR(a.torque[2], 4 * c * margin, 1e-12);
  EXPECT_NEAR(a.accel[0], 4 * 0.1 * margin / 0.02, 1e-9);
  EXPECT_NEAR(a.accel[1], 4 * 0.2 * margin / 0.04, 1e-9);
  // A heavier vehicle on the same rotors: the ceiling binds (10 - 7.3575 < 7.3575).
  const TorqueAuthority heavy = ComputeTorqueAuthority(Vehicle(3.0, {0.02, 0.04, 0.05}, rotors));
  EXPECT_NEAR(heavy.torque[0], 4 * 0.1 * (10 - 3.0 * kG / 4), 1e-12);
}

TEST(TorqueAuthority, NotComputedWithoutFourActuatorsOrWithASingularLayout) {
  const std::vector<mjfActuatorInfo> forces = {Actuator({0, 0, 0}, {1, 0, 0, 0, 0, 0}, -5, 5),
                                               Actuator({0, 0, 0}, {0, 1, 0, 0, 0, 0}, -5, 5),
                                               Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0}, -5, 5)};
  const TorqueAuthority point = ComputeTorqueAuthority(Vehicle(1, {1, 1, 1}, forces));
  EXPECT_FALSE(point.known);
  EXPECT_THAT(AuthorityText(point), HasSubstr("not computed (3 actuators"));
  // Four rotors at the centre of mass: no roll or pitch torque.
  const std::vector<mjfActuatorInfo> centre(4, Actuator({0, 0, 0}, {0, 0, 1, 0, 0, 0.1}, 0, 10));
  EXPECT_FALSE(ComputeTorqueAuthority(Vehicle(1, {1, 1, 1}, centre)).known);
}

// A 1e30 kg vehicle on 10 N rotors: the warning said "0 rad/s^2 ... infx ... att_bw 0"; it
// says the rotors cannot hold the weight, with the numbers, and nothing about torques.
TEST(TorqueAuthority, AVehicleTooHeavyToHoverIsSaidToBeSo) {
  const double c = 0.05;
  const std::vector<mjfActuatorInfo> rotors = {
      Actuator({0.2, -0.1, 0}, {0, 0, 1, 0, 0, -c}, 0, 10),
      Actuator({-0.2, 0.1, 0}, {0, 0, 1, 0, 0, -c}, 0, 10),
      Actuator({0.2, 0.1, 0}, {0, 0, 1, 0, 0, c}, 0, 10),
      Actuator({-0.2, -0.1, 0}, {0, 0, 1, 0, 0, c}, 0, 10)};
  const TorqueAuthority a = ComputeTorqueAuthority(Vehicle(1e30, {1e30, 1e30, 1e30}, rotors));
  EXPECT_FALSE(a.known);
  EXPECT_TRUE(a.cannot_hover);
  AttitudeDemand d;
  d.att_bw = 8.0;
  d.tilt_max = 0.5;
  const auto w = AuthorityWarnings(a, d, "vehicle model heavy.xml");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("vehicle model heavy.xml: the actuators cannot hold its weight "
                              "(1e+30 kg x 9.81 m/s^2 = 9.81e+30 N): hovering takes actuator 0 "
                              "to 2.45e+30, outside its ctrlrange [0, 10]: it cannot hover"));
  EXPECT_THAT(w[0], HasSubstr("lower the model's mass or raise the actuators' ctrlrange"));
  EXPECT_THAT(w[0], ::testing::Not(HasSubstr("inf")));
  EXPECT_THAT(AuthorityText(a), HasSubstr("not computed (the actuators cannot hold its weight"));
}

TEST(TorqueAuthority, DemandIsBandwidthSquaredTimesTiltLimit) {
  EXPECT_DOUBLE_EQ(DemandedTiltAcceleration(8.0, 0.5), 32.0);
  AttitudeDemand d;
  d.att_bw = 1.0;
  d.att_bw_unlimited = 12.5;
  EXPECT_EQ(d.Reference(), 12.5);  // a plugin that lowered its loop is judged by the unlimited
  d.att_bw_unlimited = 0;          // not reported
  EXPECT_EQ(d.Reference(), 1.0);
}

TEST(TorqueAuthority, WarnsWhenTheLoopAsksForMoreThanTheVehicleHas) {
  const auto weak = ThrustMoments(1e-5, 0.5e-5, 1e-5);  // pitch: 1e-5 N m on 4e-5 kg m^2
  const TorqueAuthority a = ComputeTorqueAuthority(Vehicle(0.027, {2.5e-5, 4e-5, 3e-5}, weak));
  AttitudeDemand d;
  d.att_bw = 2.0;  // given by the user: asks 2^2 x 0.5 = 2 rad/s^2, the vehicle has 0.4 / 0.25
  d.tilt_max = 0.5;
  const auto w = AuthorityWarnings(a, d, "vehicle model tiny.xml");
  ASSERT_EQ(w.size(), 2u);  // roll and pitch differ: one each
  EXPECT_THAT(w[0], HasSubstr("vehicle model tiny.xml: roll torque authority 0.4 rad/s^2"));
  EXPECT_THAT(w[0], HasSubstr("below the 2 rad/s^2 the attitude loop asks for"));
  EXPECT_THAT(w[0], HasSubstr("raise the moment ctrlrange"));
  EXPECT_THAT(w[0], HasSubstr("5x, or lower tilt_max to 0.1 rad"));       // 2 / 0.4; 0.4 / 4
  EXPECT_THAT(w[0], HasSubstr("or the attitude gains to att_bw 0.894"));  // sqrt(0.4 / 0.5)
  EXPECT_THAT(w[1], HasSubstr("pitch torque authority 0.25 rad/s^2"));
  EXPECT_THAT(w[1], ::testing::Not(HasSubstr("lowered")));
  // Enough authority for that loop: nothing.
  d.att_bw = 0.5;  // 0.125 rad/s^2
  EXPECT_TRUE(AuthorityWarnings(a, d, "v").empty());
  // A plugin that lowered its default to the authority is judged by its unlimited loop, and
  // the warning says so.
  d.att_bw_unlimited = 12.5;
  const auto lowered = AuthorityWarnings(a, d, "v");
  ASSERT_EQ(lowered.size(), 2u);
  EXPECT_THAT(lowered[0], HasSubstr("lowered its default att_bw to 0.5 rad/s"));
  EXPECT_THAT(lowered[0], HasSubstr("tuned for 12.5 rad/s, may outrun it"));
  EXPECT_THAT(lowered[0], HasSubstr("Expect rocking or flips"));  // 0.5 rad/s: below 3
  // A tilt limit the formation cannot fly with is not advised: 0.4 / 12.5^2 = 0.00256 rad.
  EXPECT_THAT(lowered[0], ::testing::Not(HasSubstr("lower tilt_max")));
  EXPECT_THAT(lowered[0], HasSubstr("no tilt limit helps at 12.5 rad/s: the one this authority "
                                    "follows, 0.00256 rad, leaves the formation too little"));
  // The published cf2 with its derived defaults: att_bw lowered to 3.0 rad/s (tilt 0.0464) flies
  // the scaled Exp 2 without an event (docs/VEHICLES.md): no flips foretold, no tilt advice.
  const TorqueAuthority cf2 = ComputeTorqueAuthority(
      Vehicle(0.027, {2.4e-5, 2.4e-5, 3e-5}, ThrustMoments(1e-5, 0.5e-5, 1e-5)));
  AttitudeDemand derived;
  derived.att_bw = 3.0;
  derived.att_bw_unlimited = 12.5;
  derived.tilt_max = 0.0464;
  const auto flies = AuthorityWarnings(cf2, derived, "cf2.xml");
  ASSERT_EQ(flies.size(), 1u);  // roll and pitch alike
  EXPECT_THAT(flies[0], HasSubstr("At 3 rad/s it is still fast enough for the stock outer loops"));
  EXPECT_THAT(flies[0], HasSubstr("expect a less precise formation, not flips"));
  EXPECT_THAT(flies[0], ::testing::Not(HasSubstr("Expect rocking or flips")));
  EXPECT_THAT(flies[0], ::testing::Not(HasSubstr("lower tilt_max")));
  // No loop reported (e.g. pointmass_direct): nothing judged.
  EXPECT_TRUE(AuthorityWarnings(a, AttitudeDemand{}, "v").empty());
}

TEST(TorqueAuthority, OneWarningWhenRollAndPitchAreAlike) {
  const auto weak = ThrustMoments(1e-5, 0.5e-5, 1e-5);  // pitch gear 2: 1e-5 N m as roll
  const TorqueAuthority a = ComputeTorqueAuthority(Vehicle(0.027, {2.5e-5, 2.5e-5, 3e-5}, weak));
  AttitudeDemand d;
  d.att_bw = 12.5;
  d.tilt_max = 0.78;
  const auto w = AuthorityWarnings(a, d, "v");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("roll and pitch torque authority 0.4 rad/s^2"));
}

}  // namespace
}  // namespace mjf::runner
