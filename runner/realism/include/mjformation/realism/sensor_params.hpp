// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The parameters of the sensor model (sensor_model.hpp): per channel white noise, bias walk,
// rate, latency and GNSS-like wander; the accelerometer; the named suites. Plain data and their
// checks, so the experiment's struct (runner/config) carries them without the model.
#ifndef MJFORMATION_REALISM_SENSOR_PARAMS_HPP_
#define MJFORMATION_REALISM_SENSOR_PARAMS_HPP_

#include <array>
#include <string>

namespace mjf::realism {

// One channel's error model. Units are the channel's: m (position), m/s (velocity), rad
// (attitude: a small rotation applied to the true attitude, in body axes), rad/s (body rate).
struct ChannelNoise {
  double white_std = 0.0;  // standard deviation of the white noise added to each sample, per axis
  double bias_walk = 0.0;  // random-walk intensity of the bias, unit/sqrt(s): var(b(t)) = q^2 t
  double rate_hz = 0.0;    // samples per second, held in between; 0: every physics step
  double latency_s = 0.0;  // age of the truth a sample reports, s (a whole number of steps)
  // GNSS-like error: a first-order Gauss-Markov wander added to each sample, stationary from the
  // start: w+ = phi w + sigma sqrt(1 - phi^2) n, phi = exp(-T / tau). The part shared by every
  // vehicle (the same satellites and atmosphere) has weight sqrt(correlation), the vehicle's own
  // sqrt(1 - correlation): each vehicle's wander has variance sigma^2, pairwise correlation rho.
  double wander_sigma = 0.0;  // unit, stationary standard deviation per axis
  double wander_tau = 100.0;  // s, correlation time (> 0)
  double correlation = 0.0;   // in [0, 1]: the common fraction of the wander's variance
};

// The accelerometer channel (for an estimator to integrate): specific force f = R^T (a - g) in body
// axes (for the point mass, whose body never rotates, that is the world frame), with white noise of
// density `noise_density` and a bias random walk; every physics step, no latency.
struct AccelNoise {
  bool enabled = false;
  double noise_density = 0.0;  // m/s^2/sqrt(Hz): per-sample std = density / sqrt(dt)
  double bias_walk = 0.0;      // m/s^3/sqrt(Hz): var(b(t)) = q^2 t
};

enum class Channel { kPosition = 0, kVelocity, kAttitude, kBodyRate };
constexpr int kChannels = 4;
const char* ChannelName(Channel c);  // "position", "velocity", "attitude", "body_rate"

struct SensorParams {
  std::array<ChannelNoise, kChannels> channel;
  AccelNoise accel;  // for estimators; off unless a suite or the accel_* keys switch it on

  ChannelNoise& operator[](Channel c) { return channel[static_cast<int>(c)]; }
  const ChannelNoise& operator[](Channel c) const { return channel[static_cast<int>(c)]; }

  // Exact pass-through: what the controllers see is the truth, bit for bit.
  static SensorParams Ideal();
  // A small UAV with a GNSS receiver, an attitude estimate and a MEMS gyro; sources in
  // sensor_model.cc and docs/REALISM.md.
  static SensorParams Typical();
  // GNSS-class suites, named for real sensor classes (numbers and sources in sensor_model.cc and
  // docs/REALISM.md); each comes with an accelerometer of the ICM-42688 class.
  static SensorParams ConsumerGnss();   // u-blox M8N class
  static SensorParams Rtk();            // u-blox ZED-F9P class
  static SensorParams MotionCapture();  // optical motion capture (Vicon / OptiTrack class)
  // The accelerometer of an IMU grade: "icm42688" (data sheet) or "ekf2" (the inflated values
  // PX4's EKF2 assumes for a vibrating airframe). False for an unknown name.
  static bool ImuGrade(const std::string& name, AccelNoise* accel);
  // White noise and bias walk multiplied by `factor` (rates and latencies unchanged).
  SensorParams Scaled(double factor) const;
  bool IsIdeal() const;
  // Empty when usable with this physics timestep, else "<channel>_<key>: reason".
  std::string Validate(double timestep) const;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_SENSOR_PARAMS_HPP_
