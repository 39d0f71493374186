// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The stock attitude plugins' default gains adapt to the vehicle's torque authority
// (AuthorityAttitudeBandwidth, types.hpp): the attitude loop k stays within sqrt(alpha /
// tilt_max), so k^2 tilt_max <= alpha; the nominal gains are kept where the authority allows
// them, explicit gains always.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "mjformation/attitude/geometric.hpp"
#include "mjformation/attitude/pd_cascade.hpp"
#include "mjformation/attitude/types.hpp"

namespace mjf::attitude {
namespace {

TEST(AuthorityGainsTest, BandwidthIsSquareRootOfAuthorityOverTiltLimit) {
  EXPECT_DOUBLE_EQ(AuthorityAttitudeBandwidth(100.0, 0.25), 20.0);
  EXPECT_DOUBLE_EQ(AuthorityAttitudeBandwidth(0.42, 0.42), 1.0);
  // The loop it gives asks exactly for the authority: k^2 tilt_max = alpha.
  const double k = AuthorityAttitudeBandwidth(0.4175, 0.78);
  EXPECT_NEAR(k * k * 0.78, 0.4175, 1e-15);
  // Nothing to cap: infinite or no authority (a vehicle that cannot hover is refused elsewhere).
  EXPECT_TRUE(std::isinf(AuthorityAttitudeBandwidth(INFINITY, 0.5)));
  EXPECT_TRUE(std::isinf(AuthorityAttitudeBandwidth(0.0, 0.5)));
}

// The default tilt limit: the nominal one unless the authority cannot follow a 3 rad/s loop from
// it, then alpha / 3^2 (so that loop asks exactly the authority: 3^2 tilt = alpha).
TEST(AuthorityGainsTest, DerivedTiltLimitKeepsTheSlowestUsableLoopWithinTheAuthority) {
  EXPECT_EQ(AuthorityTiltLimit(60.5, 0.78), 0.78);  // the Iris keeps the nominal limit
  EXPECT_EQ(AuthorityTiltLimit(38.5, 0.78), 0.78);  // the Skydio X2 too
  const double cf2 = 1e-5 / 2.4e-5;
  const double tilt = AuthorityTiltLimit(cf2, 0.78);
  EXPECT_NEAR(tilt, cf2 / (kMinAttitudeBandwidth * kMinAttitudeBandwidth), 1e-15);
  EXPECT_NEAR(AuthorityAttitudeBandwidth(cf2, tilt), kMinAttitudeBandwidth, 1e-12);
  // The edge: alpha = 3^2 x nominal keeps the nominal limit exactly, a little less lowers it.
  EXPECT_EQ(AuthorityTiltLimit(9 * 0.35, 0.35), 0.35);
  EXPECT_LT(AuthorityTiltLimit(9 * 0.35 - 1e-9, 0.35), 0.35);
  // Nothing known (infinite or non-positive authority): the nominal limit.
  EXPECT_EQ(AuthorityTiltLimit(INFINITY, 0.35), 0.35);
  EXPECT_EQ(AuthorityTiltLimit(0.0, 0.35), 0.35);
  // An explicit tilt limit is never changed by either plugin's resolution.
  PdCascade::Gains pd;
  pd.tilt_max = 0.2;
  EXPECT_EQ(PdCascade::Resolve(pd, cf2).tilt_max, 0.2);
  Geometric::Gains geo;
  geo.tilt_max = 0.2;
  EXPECT_EQ(Geometric::Resolve(geo, Geometric::Vehicle{}, {cf2, cf2, cf2}).tilt_max, 0.2);
  // The default is resolved from the weaker tilt axis.
  EXPECT_NEAR(
      Geometric::Resolve(Geometric::Gains{}, Geometric::Vehicle{}, {5.0, cf2, 100}).tilt_max,
      cf2 / 9, 1e-15);
  EXPECT_NEAR(PdCascade::Resolve(PdCascade::Gains{}, cf2).tilt_max, cf2 / 9, 1e-15);
}

Geometric::Vehicle Vehicle(double motor_lag) {
  Geometric::Vehicle v;
  v.mass = 1.5;
  v.gravity = 9.81;
  v.inertia = {0.03, 0.03, 0.05};
  v.motor_lag = motor_lag;
  v.timestep = 0.001;
  return v;
}

TEST(AuthorityGainsTest, GeometricRateLoopIsCappedByAuthorityAndTiltLimit) {
  const Geometric::Vehicle v = Vehicle(0.025);  // lag bound 0.9 / 0.027 = 33.3 rad/s
  const double lag_bound = 0.9 / 0.027;
  // Strong (the Iris: 60.5 rad/s^2 in pitch): the lag bound decides, nothing changes, and the
  // derived tilt limit is the nominal one.
  Geometric::Gains g = Geometric::Resolve(Geometric::Gains{}, v, {102, 60.5, 14.7});
  EXPECT_DOUBLE_EQ(g.rate_bw, lag_bound);
  EXPECT_DOUBLE_EQ(g.att_bw, lag_bound / 4);
  EXPECT_EQ(g.tilt_max, Geometric::kNominalTiltMax);
  // Weak (a cf2-like 0.42 rad/s^2) with the nominal tilt limit given: rate_bw = 4 sqrt(alpha /
  // tilt_max), the cascade below it.
  Geometric::Gains nominal_tilt;
  nominal_tilt.tilt_max = 0.78;
  g = Geometric::Resolve(nominal_tilt, v, {0.42, 0.42, 0.31});
  EXPECT_DOUBLE_EQ(g.rate_bw, 4 * std::sqrt(0.42 / 0.78));
  EXPECT_DOUBLE_EQ(g.att_bw, std::sqrt(0.42 / 0.78));
  EXPECT_NEAR(g.att_bw * g.att_bw * g.tilt_max, 0.42, 1e-12);  // within the authority
  EXPECT_DOUBLE_EQ(g.yaw_bw, g.att_bw / 2);
  EXPECT_DOUBLE_EQ(g.z_bw, g.att_bw / 2.5);
  // The weaker tilt axis decides.
  g = Geometric::Resolve(nominal_tilt, v, {5.0, 0.42, 100});
  EXPECT_DOUBLE_EQ(g.att_bw, std::sqrt(0.42 / 0.78));
  // A lower tilt limit lets the same vehicle fly a faster loop.
  Geometric::Gains small_tilt;
  small_tilt.tilt_max = 0.02;
  g = Geometric::Resolve(small_tilt, v, {0.42, 0.42, 0.31});
  EXPECT_DOUBLE_EQ(g.att_bw, std::sqrt(0.42 / 0.02));
  // Explicit gains are never overridden.
  Geometric::Gains given;
  given.rate_bw = 20;
  given.att_bw = 5;
  g = Geometric::Resolve(given, v, {0.42, 0.42, 0.31});
  EXPECT_EQ(g.rate_bw, 20);
  EXPECT_EQ(g.att_bw, 5);
}

TEST(AuthorityGainsTest, PdCascadeKeepsNominalGainsWhereTheAuthorityAllows) {
  PdCascade::Gains g;
  g.tilt_max = 0.55;  // the experiments' value on the Iris (60.5 rad/s^2): 150 / 22 exactly
  PdCascade::Gains r = PdCascade::Resolve(g, 60.5);
  EXPECT_EQ(r.kp_att, PdCascade::kNominalKpAtt);
  EXPECT_EQ(r.kd_att, PdCascade::kNominalKdAtt);
  r = PdCascade::Resolve(g, INFINITY);
  EXPECT_EQ(r.kp_att, 150);
  EXPECT_EQ(r.kd_att, 22);
}

TEST(AuthorityGainsTest, PdCascadeLowersBothGainsTogetherForAWeakVehicle) {
  PdCascade::Gains g;
  g.tilt_max = 0.35;  // the nominal limit, given
  const double alpha = 0.42;
  const PdCascade::Gains r = PdCascade::Resolve(g, alpha);
  // The attitude gain kp / kd lands on the bound, so (kp / kd)^2 tilt_max = alpha ...
  const double k = r.kp_att / r.kd_att;
  EXPECT_NEAR(k, std::sqrt(alpha / 0.35), 1e-12);
  EXPECT_NEAR(k * k * 0.35, alpha, 1e-12);
  // ... with the nominal damping ratio kd / (2 sqrt(kp)).
  EXPECT_NEAR(r.kd_att / (2 * std::sqrt(r.kp_att)), 22 / (2 * std::sqrt(150.0)), 1e-12);
  EXPECT_LT(r.kp_att, 150);
  // An explicit gain stays as given; only the other one is derived.
  PdCascade::Gains given;
  given.tilt_max = 0.35;
  given.kp_att = 100;
  const PdCascade::Gains rg = PdCascade::Resolve(given, alpha);
  EXPECT_EQ(rg.kp_att, 100);
  EXPECT_NEAR(rg.kd_att, r.kd_att, 1e-12);
}

TEST(AuthorityGainsTest, ControllersUseTheAdaptedGains) {
  // A thrust-and-moment vehicle (gear -1 moments, +-1e-5 N m on 2.4e-5 kg m^2: 0.4175 rad/s^2).
  std::array<RotorGeometry, Mixer::kRotors> actuators;
  actuators[0].gear = {0, 0, 1, 0, 0, 0};
  actuators[0].ctrl_max = 0.35;
  for (int i = 0; i < 3; ++i) {
    actuators[1 + i].gear = {0, 0, 0, 0, 0, 0};
    actuators[1 + i].gear[3 + i] = -1;
    actuators[1 + i].ctrl_min = -1e-5;
    actuators[1 + i].ctrl_max = 1e-5;
  }
  const double alpha = 1e-5 / 2.4e-5;
  // The defaults: the tilt limit lowered to alpha / 3^2, the loop then at 3 rad/s.
  const PdCascade pd(PdCascade::Gains{}, PdCascade::Vehicle{0.027, 9.81, {2.4e-5, 2.4e-5, 3.2e-5}},
                     actuators);
  EXPECT_NEAR(pd.gains().tilt_max, alpha / 9, 1e-12);
  EXPECT_NEAR(pd.gains().kp_att / pd.gains().kd_att, kMinAttitudeBandwidth, 1e-9);
  EXPECT_NEAR(pd.unlimited_att_bw(), 150.0 / 22.0, 1e-12);
  Geometric::Vehicle v;
  v.mass = 0.027;
  v.gravity = 9.81;
  v.inertia = {2.4e-5, 2.4e-5, 3.2e-5};
  v.timestep = 0.001;
  const Geometric geo(Geometric::Gains{}, v, actuators);
  EXPECT_NEAR(geo.gains().tilt_max, alpha / 9, 1e-12);
  EXPECT_NEAR(geo.gains().att_bw, kMinAttitudeBandwidth, 1e-9);
  // With the nominal tilt limit given, the loop is capped to what that tilt allows instead.
  Geometric::Gains nominal_tilt;
  nominal_tilt.tilt_max = 0.78;
  const Geometric geo_given(nominal_tilt, v, actuators);
  EXPECT_EQ(geo_given.gains().tilt_max, 0.78);
  EXPECT_NEAR(geo_given.gains().att_bw, std::sqrt(alpha / 0.78), 1e-9);
  EXPECT_DOUBLE_EQ(geo.unlimited_att_bw(), 50.0 / 4);  // sampling bound 0.05 / 1 ms, / 4
}

}  // namespace
}  // namespace mjf::attitude
