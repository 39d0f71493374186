// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/sensor_params.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "mjformation/time_steps.hpp"

namespace mjf::realism {

const char* ChannelName(Channel c) {
  static const char* const kNames[kChannels] = {"position", "velocity", "attitude", "body_rate"};
  return kNames[static_cast<int>(c)];
}

SensorParams SensorParams::Ideal() { return SensorParams{}; }

// A typical small UAV as the controllers of this simulator would see it (no state estimator in
// between; see docs/REALISM.md for the discussion of what that implies):
//  position  u-blox NEO-M8N data sheet (UBX-15031086): 2.5 m CEP horizontal, navigation rate up to
//            10 Hz. The CEP is mostly slowly wandering error, modelled as the bias walk
//            0.05 m/sqrt(s) (1.6 m after 1000 s); the sample-to-sample noise is PX4 EKF2's default
//            GNSS position noise EKF2_GPS_P_NOISE = 0.5 m. Latency: PX4's EKF2_GPS_DELAY = 110 ms.
//  velocity  u-blox NEO-M8N: 0.05 m/s (50 %) speed accuracy; taken as 0.1 m/s per axis, 10 Hz,
//            the same 110 ms latency, no bias.
//  attitude  an attitude estimate from a MEMS IMU: 0.01 rad (0.6 deg) white, 0.0005 rad/sqrt(s)
//            drift, at PX4's 250 Hz attitude loop, no latency (our assumption, typical of EKF tilt
//            errors of 0.5-1 deg).
//  body rate PX4 SITL Gazebo Iris IMU (sitl_gazebo models/iris/iris.sdf): gyroscopeNoiseDensity
//            1.8665e-4 rad/s/sqrt(Hz), i.e. 0.0059 rad/s per sample at 1 kHz, and
//            gyroscopeRandomWalk 3.8785e-5 rad/s^2/sqrt(Hz) as the bias walk; every step.
SensorParams SensorParams::Typical() {
  SensorParams p;
  p[Channel::kPosition] = {0.5, 0.05, 10.0, 0.11};
  p[Channel::kVelocity] = {0.1, 0.0, 10.0, 0.11};
  p[Channel::kAttitude] = {0.01, 0.0005, 250.0, 0.0};
  p[Channel::kBodyRate] = {1.8665e-4 * std::sqrt(1000.0), 3.8785e-5, 0.0, 0.0};
  return p;
}

// The GNSS-class suites. Attitude and body rate: the attitude channel as in Typical (an autopilot's
// attitude estimate), the gyro of the ICM-42688 class. Accelerometer: ImuGrade("icm42688").
//  ConsumerGnss  u-blox NEO-M8N data sheet (UBX-15031086): 2.5 m CEP horizontal, 0.05 m/s
//                velocity (50 %), up to 10 Hz. The CEP is taken as mostly wander: for a circular
//                normal CEP = 1.1774 sigma, so sigma = 2.12 m per axis, tau = 100 s (our
//                assumption: the slow drift of the satellite geometry and the ionosphere); the
//                sample-to-sample jitter 0.3 m is our assumption (EKF2_GPS_P_NOISE = 0.5 m is
//                the floor EKF2 assumes when fusing, not the jitter). Receivers metres apart see
//                the same satellites and atmosphere: correlation 0.9 (our assumption). Latency
//                110 ms (PX4 EKF2_GPS_DELAY).
//  Rtk           u-blox ZED-F9P data sheet: RTK 0.01 m + 1 ppm CEP, 0.05 m/s, up to 20 Hz; white
//                0.01 m, wander 0.005 m over 60 s with correlation 0.5 (our assumption: the
//                base station's error is common), latency 50 ms (our assumption).
//  MotionCapture optical motion capture (Vicon / OptiTrack class): sub-mm positions (0.3 mm
//                white), 100-360 Hz (200 Hz here), 6-26 ms end to end (10 ms here); velocity by
//                the system's differentiation, 0.02 m/s; attitude 0.002 rad (our assumption).
//  gyro          TDK ICM-42688-P data sheet: 0.0028 dps/sqrt(Hz) = 4.89e-5 rad/s/sqrt(Hz), i.e.
//                1.55e-3 rad/s per sample at 1 kHz; bias walk as Typical (3.88e-5).
namespace {
ChannelNoise Icm42688Gyro() { return {4.887e-5 * std::sqrt(1000.0), 3.8785e-5, 0.0, 0.0}; }
}  // namespace

SensorParams SensorParams::ConsumerGnss() {
  SensorParams p = Typical();
  p[Channel::kPosition] = {0.3, 0.0, 10.0, 0.11, 2.5 / 1.1774, 100.0, 0.9};
  p[Channel::kVelocity] = {0.05, 0.0, 10.0, 0.11};
  p[Channel::kBodyRate] = Icm42688Gyro();
  ImuGrade("icm42688", &p.accel);
  return p;
}

SensorParams SensorParams::Rtk() {
  SensorParams p = Typical();
  p[Channel::kPosition] = {0.01, 0.0, 20.0, 0.05, 0.005, 60.0, 0.5};
  p[Channel::kVelocity] = {0.05, 0.0, 20.0, 0.05};
  p[Channel::kBodyRate] = Icm42688Gyro();
  ImuGrade("icm42688", &p.accel);
  return p;
}

SensorParams SensorParams::MotionCapture() {
  SensorParams p;
  p[Channel::kPosition] = {0.0003, 0.0, 200.0, 0.01};
  p[Channel::kVelocity] = {0.02, 0.0, 200.0, 0.01};
  p[Channel::kAttitude] = {0.002, 0.0, 200.0, 0.01};
  p[Channel::kBodyRate] = Icm42688Gyro();
  ImuGrade("icm42688", &p.accel);
  return p;
}

// icm42688: TDK ICM-42688-P data sheet, accelerometer noise 75 ug/sqrt(Hz) = 7.355e-4
//           m/s^2/sqrt(Hz); its bias instability is not a random-walk figure: 1e-4 m/s^3/sqrt(Hz)
//           is our assumption. ekf2: PX4 EKF2_ACC_NOISE = 0.35 m/s^2 and EKF2_ACC_B_NOISE =
//           0.003 m/s^3, inflated for airframe vibration.
bool SensorParams::ImuGrade(const std::string& name, AccelNoise* accel) {
  if (name == "icm42688") {
    *accel = {true, 75e-6 * 9.80665, 1e-4};
  } else if (name == "ekf2") {
    *accel = {true, 0.35, 0.003};
  } else {
    return false;
  }
  return true;
}

SensorParams SensorParams::Scaled(double factor) const {
  SensorParams p = *this;
  for (ChannelNoise& c : p.channel) {
    c.white_std *= factor;
    c.bias_walk *= factor;
    c.wander_sigma *= factor;
  }
  p.accel.noise_density *= factor;
  p.accel.bias_walk *= factor;
  return p;
}

bool SensorParams::IsIdeal() const {
  for (const ChannelNoise& c : channel) {
    if (c.white_std != 0 || c.bias_walk != 0 || c.latency_s != 0 || c.wander_sigma != 0) {
      return false;
    }
    // Any rate is a pass-through only when it samples every step; checked in SensorModel.
    if (c.rate_hz != 0) return false;
  }
  return true;
}

namespace {

// The largest noise each channel accepts, in its units: far beyond any real sensor (every
// preset at the largest `scale`, 100, stays inside), and small enough that the squares and sums
// an estimator forms of them stay finite (1e300 m would make a kf_ins variance infinite).
struct NoiseLimits {
  double std;        // white_std and wander_sigma: m, m/s, rad, rad/s
  double bias_walk;  // per sqrt(s)
  const char* unit;
};
constexpr NoiseLimits kNoiseLimits[kChannels] = {
    {1000.0, 100.0, "m"}, {100.0, 100.0, "m/s"}, {3.2, 1.0, "rad"}, {100.0, 10.0, "rad/s"}};
constexpr double kMaxAccelNoise = 100.0;    // m/s^2/sqrt(Hz)
constexpr double kMaxAccelBiasWalk = 10.0;  // m/s^3/sqrt(Hz)

// "" when 0 <= value <= max, else "KEY: must be a number in [0, MAX] UNIT".
std::string InRange(const std::string& key, double value, double max, const std::string& unit) {
  if (value >= 0 && value <= max) return "";
  char text[64];
  std::snprintf(text, sizeof(text), "%g", max);
  return key + ": must be a number in [0, " + text + "] " + unit;
}

std::string CheckNoise(const ChannelNoise& c, const std::string& name, const NoiseLimits& max) {
  const std::string unit = max.unit;
  for (const std::string& problem :
       {InRange(name + "_std", c.white_std, max.std, unit),
        InRange(name + "_bias_walk", c.bias_walk, max.bias_walk, unit + "/sqrt(s)"),
        InRange(name + "_wander", c.wander_sigma, max.std, unit)}) {
    if (!problem.empty()) return problem;
  }
  return "";
}

}  // namespace

std::string SensorParams::Validate(double timestep) const {
  for (int k = 0; k < kChannels; ++k) {
    const ChannelNoise& c = channel[k];
    const std::string name = ChannelName(static_cast<Channel>(k));
    const std::string noise = CheckNoise(c, name, kNoiseLimits[k]);
    if (!noise.empty()) return noise;
    if (!(c.rate_hz >= 0) || !std::isfinite(c.rate_hz)) {
      return name + "_rate: must be a finite number >= 0 Hz (0: every physics step)";
    }
    if (c.rate_hz > 0 && WholeSteps(1.0 / c.rate_hz, timestep) < 1) {
      return name + "_rate: 1 / rate must be a whole number (>= 1) of physics steps of " +
             std::to_string(timestep) + " s";
    }
    if (!(c.latency_s >= 0) || !std::isfinite(c.latency_s)) {
      return name + "_latency: must be a finite number >= 0 s";
    }
    if (WholeSteps(c.latency_s, timestep) < 0) {
      return name + "_latency: must be a whole number of physics steps of " +
             std::to_string(timestep) + " s";
    }
    if (c.latency_s > 10.0) return name + "_latency: must be <= 10 s";
    if (!(c.wander_tau > 0) || !std::isfinite(c.wander_tau)) {
      return name + "_wander_tau: must be a finite number > 0 s";
    }
    if (!(c.correlation >= 0 && c.correlation <= 1)) {
      return name + "_correlation: must be in [0, 1]";
    }
  }
  const std::string noise =
      InRange("accel_noise", accel.noise_density, kMaxAccelNoise, "m/s^2/sqrt(Hz)");
  if (!noise.empty()) return noise;
  return InRange("accel_bias_walk", accel.bias_walk, kMaxAccelBiasWalk, "m/s^3/sqrt(Hz)");
}

}  // namespace mjf::realism
