// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace mjf::realism {
namespace {

// Steps of `seconds` at `timestep`, or -1 when it is not a whole number of steps.
int64_t WholeSteps(double seconds, double timestep) {
  const double steps = seconds / timestep;
  const double rounded = std::round(steps);
  return std::abs(steps - rounded) <= 1e-6 * std::max(1.0, rounded) ? static_cast<int64_t>(rounded)
                                                                    : -1;
}

// q (w x y z) rotated by the small body-axes rotation vector e: q * exp(e / 2).
void Perturb(const double q[4], const double e[3], double out[4]) {
  const double angle = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  double d[4] = {1, 0, 0, 0};
  if (angle > 0) {
    const double s = std::sin(0.5 * angle) / angle;
    d[0] = std::cos(0.5 * angle);
    d[1] = s * e[0];
    d[2] = s * e[1];
    d[3] = s * e[2];
  }
  out[0] = q[0] * d[0] - q[1] * d[1] - q[2] * d[2] - q[3] * d[3];
  out[1] = q[0] * d[1] + q[1] * d[0] + q[2] * d[3] - q[3] * d[2];
  out[2] = q[0] * d[2] - q[1] * d[3] + q[2] * d[0] + q[3] * d[1];
  out[3] = q[0] * d[3] + q[1] * d[2] - q[2] * d[1] + q[3] * d[0];
}

}  // namespace

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

SensorParams SensorParams::Scaled(double factor) const {
  SensorParams p = *this;
  for (ChannelNoise& c : p.channel) {
    c.white_std *= factor;
    c.bias_walk *= factor;
  }
  return p;
}

bool SensorParams::IsIdeal() const {
  for (const ChannelNoise& c : channel) {
    if (c.white_std != 0 || c.bias_walk != 0 || c.latency_s != 0) return false;
    // Any rate is a pass-through only when it samples every step; checked in SensorModel.
    if (c.rate_hz != 0) return false;
  }
  return true;
}

std::string SensorParams::Validate(double timestep) const {
  for (int k = 0; k < kChannels; ++k) {
    const ChannelNoise& c = channel[k];
    const std::string name = ChannelName(static_cast<Channel>(k));
    if (!(c.white_std >= 0) || !std::isfinite(c.white_std)) {
      return name + "_std: must be a finite number >= 0";
    }
    if (!(c.bias_walk >= 0) || !std::isfinite(c.bias_walk)) {
      return name + "_bias_walk: must be a finite number >= 0";
    }
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
  }
  return "";
}

SensorModel::SensorModel(const SensorParams& params, double timestep, uint64_t seed)
    : ideal_(params.IsIdeal()), timestep_(timestep), normal_(seed) {
  const std::string problem = params.Validate(timestep);
  if (!problem.empty()) throw std::invalid_argument("sensor model: " + problem);
  for (int k = 0; k < kChannels; ++k) {
    ChannelState& ch = channels_[k];
    ch.noise = params.channel[k];
    ch.dim = static_cast<Channel>(k) == Channel::kAttitude ? 4 : 3;
    ch.period_steps = ch.noise.rate_hz > 0 ? WholeSteps(1.0 / ch.noise.rate_hz, timestep) : 1;
    ch.latency_steps = WholeSteps(ch.noise.latency_s, timestep);
    ch.bias_every = std::max<int64_t>(
        1, static_cast<int64_t>(std::floor(0.01 / (ch.period_steps * timestep) + 1e-9)));
    ch.history.assign(static_cast<size_t>(ch.latency_steps + 1) * ch.dim, 0.0);
  }
}

void SensorModel::StepChannel(ChannelState& ch, int64_t step, const double* truth) {
  const int64_t slots = ch.latency_steps + 1;
  std::memcpy(ch.history.data() + ch.write_slot * ch.dim, truth, sizeof(double) * ch.dim);
  // The truth the sensor reports now is `latency` steps old: the slot after this step's in the
  // ring (step 0's, in slot 0, until that much history exists).
  const int64_t read_slot =
      step < ch.latency_steps ? 0 : (ch.write_slot + 1 == slots ? 0 : ch.write_slot + 1);
  ch.write_slot = ch.write_slot + 1 == slots ? 0 : ch.write_slot + 1;
  // Truth step seen = max(step - latency, 0); a new sample when it is a multiple of the period.
  if (step <= ch.latency_steps && ch.last_sample == 0) return;      // still step 0's sample: hold
  if (ch.last_sample >= 0 && ++ch.phase < ch.period_steps) return;  // hold
  ch.phase = 0;
  const double* delayed = ch.history.data() + read_slot * ch.dim;
  if (ch.last_sample >= 0 && ch.noise.bias_walk > 0 && ++ch.bias_count == ch.bias_every) {
    // Bias random walk over bias_every sample periods: b += q sqrt(interval) n, so
    // var(b(t)) = q^2 t.
    ch.bias_count = 0;
    const double scale =
        ch.noise.bias_walk * std::sqrt(ch.bias_every * ch.period_steps * timestep_);
    for (double& b : ch.bias) b += scale * normal_.Next();
  }
  ch.last_sample = std::max<int64_t>(step - ch.latency_steps, 0);
  double error[3];
  for (int a = 0; a < 3; ++a) {
    error[a] = ch.bias[a] + (ch.noise.white_std > 0 ? ch.noise.white_std * normal_.Next() : 0.0);
  }
  if (ch.dim == 4) {
    Perturb(delayed, error, ch.held.data());
  } else {
    for (int a = 0; a < 3; ++a) ch.held[a] = delayed[a] + error[a];
  }
}

void SensorModel::Measure(int64_t step, const mjfVehicleState& truth, mjfVehicleState* measured) {
  if (step != next_step_) {
    throw std::logic_error("SensorModel::Measure: expected step " + std::to_string(next_step_) +
                           ", got " + std::to_string(step));
  }
  ++next_step_;
  if (ideal_) {
    *measured = truth;
    return;
  }
  const double* sources[kChannels] = {truth.pos, truth.vel, truth.quat, truth.gyro};
  double* targets[kChannels] = {measured->pos, measured->vel, measured->quat, measured->gyro};
  for (int k = 0; k < kChannels; ++k) {
    ChannelState& ch = channels_[k];
    StepChannel(ch, step, sources[k]);
    std::memcpy(targets[k], ch.held.data(), sizeof(double) * ch.dim);
  }
}

}  // namespace mjf::realism
