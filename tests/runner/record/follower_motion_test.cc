// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// FollowerMotion (RMS tilt, rocking frequency, thrust variation) on synthetic signals with known
// answers.
#include "mjformation/record/follower_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mjf::runner {
namespace {

// Body -> world quaternion of a tilt `angle` about the horizontal axis at azimuth `axis`.
void TiltQuat(double angle, double axis, double q[4]) {
  q[0] = std::cos(angle / 2);
  q[1] = std::sin(angle / 2) * std::cos(axis);
  q[2] = std::sin(angle / 2) * std::sin(axis);
  q[3] = 0;
}

TEST(FollowerMotionTest, RmsTiltFrequencyAndThrustVariationOfKnownSignals) {
  FollowerMotion motion(3, 25, 40);
  const double rock_hz = 1.3, amplitude = 0.35;  // follower 0: rocks +-20 deg about x at 1.3 Hz
  for (int k = 0; k <= 1500; ++k) {              // 15 s at 100 Hz, as Exp 2's window
    const double t = 25 + 0.01 * k;
    motion.Begin(t);
    double q[4];
    const double roll = amplitude * std::sin(2 * M_PI * rock_hz * t);
    TiltQuat(std::abs(roll), roll >= 0 ? 0 : M_PI, q);
    motion.Add(0, q, 15 + 2 * std::sin(2 * M_PI * rock_hz * t));  // thrust 15 +- 2 N
    // follower 1: a steady 0.15 rad tilt whose direction turns at 0.05 Hz (the circle), plus a
    // small 0.6 Hz rocking: the rocking is what the band 0.2-5 Hz reports.
    const double dir = 2 * M_PI * 0.05 * t;
    TiltQuat(0.15 + 0.02 * std::sin(2 * M_PI * 0.6 * t), dir, q);
    motion.Add(1, q, 15);
    const double level[4] = {1, 0, 0, 0};  // follower 2: never moves
    motion.Add(2, level, 14.7);
  }
  nlohmann::ordered_json m;
  motion.AddTo(&m);
  EXPECT_NEAR(m["rms_tilt_deg_in_window"][0].get<double>(), amplitude / std::sqrt(2) * 180 / M_PI,
              0.2);
  EXPECT_NEAR(m["tilt_oscillation_hz_in_window"][0].get<double>(), rock_hz, 0.02);
  EXPECT_NEAR(m["rms_thrust_variation_n_in_window"][0].get<double>(), 2 / std::sqrt(2), 0.01);
  // A rocking of the tilt's size while its direction turns at 0.05 Hz shows in the world x and y
  // components at 0.6 +- 0.05 Hz: the metric is good to the formation's turn rate.
  EXPECT_NEAR(m["tilt_oscillation_hz_in_window"][1].get<double>(), 0.6, 0.05 + 0.01);
  EXPECT_NEAR(m["rms_tilt_deg_in_window"][1].get<double>(), 0.15 * 180 / M_PI, 0.1);
  EXPECT_TRUE(m["tilt_oscillation_hz_in_window"][2].is_null());
  // Only the slow turn of a steady tilt (below the band): no peak inside it, null.
  FollowerMotion slow(1, 25, 40);
  for (int k = 0; k <= 1500; ++k) {
    const double t = 25 + 0.01 * k;
    slow.Begin(t);
    double q[4];
    TiltQuat(0.15, 2 * M_PI * 0.05 * t, q);
    slow.Add(0, q, 15);
  }
  EXPECT_TRUE(std::isnan(slow.DominantHz(0)));
  EXPECT_DOUBLE_EQ(m["rms_thrust_variation_n_in_window"][2].get<double>(), 0);
  EXPECT_DOUBLE_EQ(m["rms_tilt_deg_in_window"][2].get<double>(), 0);
}

// Large swarms: spectra only for the first kMaxSpectra followers, RMS for all.
TEST(FollowerMotionTest, FrequencyOnlyForTheFirstFollowersOfALargeSwarm) {
  const int n = FollowerMotion::kMaxSpectra + 2;
  FollowerMotion motion(n, 0, 10);
  for (int k = 0; k <= 1000; ++k) {
    const double t = 0.01 * k;
    motion.Begin(t);
    double q[4];
    TiltQuat(0.2 * std::sin(2 * M_PI * 1.0 * t), 0, q);
    for (int i = 0; i < n; ++i) motion.Add(i, q, 10);
  }
  EXPECT_NEAR(motion.DominantHz(0), 1.0, 0.02);
  EXPECT_NEAR(motion.DominantHz(n - 3), 1.0, 0.02);
  EXPECT_TRUE(std::isnan(motion.DominantHz(n - 1)));
  nlohmann::ordered_json m;
  motion.AddTo(&m);
  EXPECT_NEAR(m["rms_tilt_deg_in_window"][n - 1].get<double>(),
              m["rms_tilt_deg_in_window"][0].get<double>(), 1e-12);
}

TEST(FollowerMotionTest, CollectiveForceOfRotorsAndOfAPointMass) {
  mjfActuatorInfo rotors[4] = {};
  for (auto& r : rotors) r.gear[2] = 1;
  const double thrusts[4] = {3, 4, 3.5, 4.5};
  EXPECT_DOUBLE_EQ(CollectiveForce(thrusts, rotors, 4), 15);
  mjfActuatorInfo axes[3] = {};
  for (int j = 0; j < 3; ++j) axes[j].gear[j] = 1;
  const double force[3] = {3, 0, 4};
  EXPECT_DOUBLE_EQ(CollectiveForce(force, axes, 3), 5);
}

}  // namespace
}  // namespace mjf::runner
