// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The rotor allocation refuses layouts without authority on an axis and says, for a singular
// one, which axes and which rotors are dependent; a thrust-and-moment vehicle (one thrust, three
// body moments, Menagerie's Crazyflie style) allocates axis by axis.
#include "mjformation/attitude/mixer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "error_of.hpp"

namespace mjf::attitude {
namespace {

using Rotors = std::array<RotorGeometry, Mixer::kRotors>;

// An X quadrotor, arms of 0.1 m, rotor k at 45 + 90 k deg; yaw torque 0.01 m per newton with
// the signs given.
Rotors XQuad(const std::array<double, 4>& yaw_sign) {
  const double a = 0.1 / std::sqrt(2.0);
  const double x[] = {a, -a, -a, a}, y[] = {a, a, -a, -a};
  Rotors r;
  for (int k = 0; k < 4; ++k) {
    r[k].pos = {x[k], y[k], 0};
    r[k].gear = {0, 0, 1, 0, 0, 0.01 * yaw_sign[k]};
    r[k].ctrl_min = 0;
    r[k].ctrl_max = 10;
  }
  return r;
}

std::string ErrorOf(const Rotors& r) {
  return mjf::testing::ErrorOf<std::invalid_argument>([&] { Mixer m(r); }, "(no error)");
}

TEST(MixerTest, CentreOfMassLayoutHasNoRollAuthority) {
  Rotors r = XQuad({1, -1, 1, -1});
  for (auto& rotor : r) rotor.pos = {0, 0, 0};  // four "rotors" on one site at the centre
  const std::string e = ErrorOf(r);
  EXPECT_NE(e.find("no roll torque authority: none of rotors 0-3"), std::string::npos) << e;
}

TEST(MixerTest, YawSingularLayoutNamesTheDependentAxesAndRotors) {
  // Rotors 0 and 1 (both at +y) turn the same way, 2 and 3 (both at -y) the other way: the yaw
  // torque of each rotor is its roll torque times 0.01 / (0.1 / sqrt 2).
  const std::string e = ErrorOf(XQuad({1, 1, -1, -1}));
  EXPECT_NE(e.find("yaw torque is proportional to roll torque (yaw torque = 0.141 x roll torque"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("; rotor0 ("), std::string::npos) << e;
  // A readable condition number and the way to the documented fix.
  EXPECT_NE(e.find("(condition number 2.26e+18)"), std::string::npos) << e;
  EXPECT_NE(e.find("docs/VEHICLES.md"), std::string::npos) << e;
  EXPECT_EQ(ErrorOf(XQuad({1, -1, 1, -1})), "(no error)");
}

TEST(MixerTest, ThrustAndMomentVehicleAllocatesAxisByAxis) {
  // Menagerie cf2's actuators: thrust gear +z in [0, 0.35] N, moments of gear -1 in +-1e-5 N m.
  Rotors r;
  r[0].gear = {0, 0, 1, 0, 0, 0};
  r[0].ctrl_min = 0;
  r[0].ctrl_max = 0.35;
  for (int i = 0; i < 3; ++i) {
    r[1 + i].gear = {0, 0, 0, 0, 0, 0};
    r[1 + i].gear[3 + i] = -1;
    r[1 + i].ctrl_min = -1e-5;
    r[1 + i].ctrl_max = 1e-5;
  }
  const Mixer m(r);
  EXPECT_NEAR(m.condition_number(), 1, 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.TorqueAuthority(i, 0.265), 1e-5, 1e-18);
  const Mixer::Result out = m.Mix(Wrench(0.2, 4e-6, -2e-6, 1e-6), Mixer::Priority::kRollPitchFirst);
  EXPECT_NEAR(out.ctrl[0], 0.2, 1e-15);
  EXPECT_NEAR(out.ctrl[1], -4e-6, 1e-18);  // the negative gear flips the sign
  EXPECT_NEAR(out.ctrl[2], 2e-6, 1e-18);
  EXPECT_NEAR(out.ctrl[3], -1e-6, 1e-18);
  // Beyond the moment range: the torque is cut into the range, the thrust stays.
  const Mixer::Result cut = m.Mix(Wrench(0.2, 1e-3, 0, 0), Mixer::Priority::kRollPitchFirst);
  EXPECT_NEAR(cut.ctrl[1], -1e-5, 1e-18);
  EXPECT_NEAR(cut.ctrl[0], 0.2, 1e-15);
}

TEST(MixerTest, XQuadTorqueAuthorityAtHover) {
  const Mixer m(XQuad({1, -1, 1, -1}));
  // Roll: rotors 0, 1 (+y) against 2, 3 (-y); at 4 N of collective each gives 1 N, at most
  // 1 N more or less (floor 0): 4 x 1 N x a.
  EXPECT_NEAR(m.TorqueAuthority(0, 4.0), 4 * 0.1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(m.TorqueAuthority(2, 4.0), 4 * 0.01, 1e-12);
}

// Thrust first, each stage's scale is the smallest quotient room / delta over the rotors, capped
// at 1 and floored at 0 (Mixer::MaxScale, which divides only when the quotient can be below 1):
// the same numbers, bit for bit, as dividing every rotor out, over wrenches that saturate the
// collective, the roll/pitch torque, the yaw torque or none.
double ScaleByDivision(const Eigen::Vector4d& base, const Eigen::Vector4d& delta,
                       const Rotors& rotors) {
  double s = 1;
  for (int k = 0; k < Mixer::kRotors; ++k) {
    if (delta[k] > 0) s = std::min(s, (rotors[k].ctrl_max - base[k]) / delta[k]);
    if (delta[k] < 0) s = std::min(s, (rotors[k].ctrl_min - base[k]) / delta[k]);
  }
  return std::max(s, 0.0);
}

TEST(MixerTest, ThrustFirstScalesAreTheRotorsQuotients) {
  const Rotors rotors = XQuad({1, -1, 1, -1});
  const Mixer m(rotors);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> thrust(-5, 60), torque(-6, 6), yaw(-1, 1);
  int saturated[3] = {0, 0, 0};
  for (int i = 0; i < 20000; ++i) {
    // A quarter of the torques tiny: unsaturated stages, where no quotient falls below 1.
    const double small = i % 4 == 0 ? 1e-3 : 1.0;
    const Wrench wanted(thrust(random), small * torque(random), small * torque(random),
                        small * yaw(random));
    const Mixer::Result r = m.Mix(wanted);
    const Eigen::Vector4d u_thrust = m.inverse().col(0) * wanted[0];
    const Eigen::Vector4d u_roll_pitch =
        m.inverse().col(1) * wanted[1] + m.inverse().col(2) * wanted[2];
    const Eigen::Vector4d u_yaw = m.inverse().col(3) * wanted[3];
    const double thrust_scale = ScaleByDivision(Eigen::Vector4d::Zero(), u_thrust, rotors);
    Eigen::Vector4d u = thrust_scale * u_thrust;
    const double roll_pitch_scale = ScaleByDivision(u, u_roll_pitch, rotors);
    u += roll_pitch_scale * u_roll_pitch;
    const double yaw_scale = ScaleByDivision(u, u_yaw, rotors);
    ASSERT_EQ(r.thrust, thrust_scale * wanted[0]) << i;
    ASSERT_EQ(r.roll_pitch_scale, roll_pitch_scale) << i;
    ASSERT_EQ(r.yaw_scale, yaw_scale) << i;
    saturated[0] += thrust_scale < 1;
    saturated[1] += roll_pitch_scale < 1;
    saturated[2] += yaw_scale < 1;
  }
  // Every stage was both saturated and not, many times.
  for (const int n : saturated) {
    EXPECT_GT(n, 1000);
    EXPECT_LT(n, 19000);
  }
}

}  // namespace
}  // namespace mjf::attitude
