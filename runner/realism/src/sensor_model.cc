// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "mjformation/time_steps.hpp"

namespace mjf::realism {
namespace {

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

SensorModel::SensorModel(const SensorParams& params, double timestep, uint64_t seed,
                         uint64_t own_seed, uint64_t common_seed)
    : ideal_(params.IsIdeal()),
      timestep_(timestep),
      normal_(seed),
      own_normal_(own_seed),
      common_normal_(common_seed),
      accel_(params.accel) {
  const std::string problem = params.Validate(timestep);
  if (!problem.empty()) throw std::invalid_argument("sensor model: " + problem);
  for (int k = 0; k < kChannels; ++k) {
    ChannelState& ch = channels_[k];
    ch.noise = params.channel[k];
    ch.dim = static_cast<Channel>(k) == Channel::kAttitude ? 4 : 3;
    ch.period_steps = ch.noise.rate_hz > 0 ? WholeSteps(1.0 / ch.noise.rate_hz, timestep) : 1;
    ch.latency_steps = WholeSteps(ch.noise.latency_s, timestep);
    ch.bias_every = std::max<int64_t>(1, StepsAtOrBefore(0.01, ch.period_steps * timestep));
    ch.history.assign(static_cast<size_t>(ch.latency_steps + 1) * ch.dim, 0.0);
    ch.wander_phi = std::exp(-ch.period_steps * timestep / ch.noise.wander_tau);
  }
}

// The Gauss-Markov wander of one new sample (both parts), added to `error`. The first sample
// draws from the stationary distribution; the common part's stream is the same in every
// vehicle's model, so every vehicle computes the same common realisation.
void SensorModel::StepWander(ChannelState& ch, bool first, double error[3]) {
  const double sigma = ch.noise.wander_sigma, phi = ch.wander_phi;
  const double drive = first ? sigma : sigma * std::sqrt(1.0 - phi * phi);
  const double keep = first ? 0.0 : phi;
  const double w_common = std::sqrt(ch.noise.correlation);
  const double w_own = std::sqrt(1.0 - ch.noise.correlation);
  for (int a = 0; a < 3; ++a) {
    ch.wander_common[a] = keep * ch.wander_common[a] + drive * common_normal_.Next();
    ch.wander_own[a] = keep * ch.wander_own[a] + drive * own_normal_.Next();
    error[a] += w_common * ch.wander_common[a] + w_own * ch.wander_own[a];
  }
}

void SensorModel::StepChannel(ChannelState& ch, int64_t step, const double* truth) {
  const int64_t slots = ch.latency_steps + 1;
  std::memcpy(ch.history.data() + ch.write_slot * ch.dim, truth, sizeof(double) * ch.dim);
  ++ch.written_since_walk;
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
  const bool first = ch.last_sample < 0;
  ch.last_sample = std::max<int64_t>(step - ch.latency_steps, 0);
  ch.fresh = true;
  double error[3];
  for (int a = 0; a < 3; ++a) {
    error[a] = ch.bias[a] + (ch.noise.white_std > 0 ? ch.noise.white_std * normal_.Next() : 0.0);
  }
  if (ch.noise.wander_sigma > 0) StepWander(ch, first, error);
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
  fresh_.clear();
  if (ideal_) {
    *measured = truth;
    // Ideal sensors: a fresh exact position and velocity every step.
    for (Channel c : {Channel::kPosition, Channel::kVelocity}) {
      const double* v = c == Channel::kPosition ? truth.pos : truth.vel;
      fresh_.push_back({c, step, {v[0], v[1], v[2]}, 0.0});
    }
    return;
  }
  const double* sources[kChannels] = {truth.pos, truth.vel, truth.quat, truth.gyro};
  double* targets[kChannels] = {measured->pos, measured->vel, measured->quat, measured->gyro};
  for (int k = 0; k < kChannels; ++k) {
    ChannelState& ch = channels_[k];
    ch.fresh = false;
    StepChannel(ch, step, sources[k]);
    std::memcpy(targets[k], ch.held.data(), sizeof(double) * ch.dim);
    if (ch.fresh && k <= static_cast<int>(Channel::kVelocity)) {
      const double stated = std::hypot(ch.noise.white_std, ch.noise.wander_sigma);
      fresh_.push_back(
          {static_cast<Channel>(k), ch.last_sample, {ch.held[0], ch.held[1], ch.held[2]}, stated});
    }
  }
}

void SensorModel::Accelerometer(int64_t step, const mjfVehicleState& truth,
                                const mjfVehicleState& measured, double gravity,
                                double accel_out[3], double quat_out[4]) {
  // Step 0 has no interval behind it: at rest, level.
  const mjfVehicleState& before = step == 0 ? truth : previous_truth_;
  const mjfVehicleState& seen = step == 0 ? measured : previous_measured_;
  double a[3];
  for (int k = 0; k < 3; ++k) a[k] = step == 0 ? 0.0 : (truth.vel[k] - before.vel[k]) / timestep_;
  a[2] += gravity;  // a - g, g = (0, 0, -gravity)
  // R^T v with R the rotation of `before.quat` (w x y z): v - 2 w (u x v) + 2 u x (u x v).
  const double* q = before.quat;
  const double u[3] = {q[1], q[2], q[3]};
  const double t[3] = {2 * (u[1] * a[2] - u[2] * a[1]), 2 * (u[2] * a[0] - u[0] * a[2]),
                       2 * (u[0] * a[1] - u[1] * a[0])};
  const double ut[3] = {u[1] * t[2] - u[2] * t[1], u[2] * t[0] - u[0] * t[2],
                        u[0] * t[1] - u[1] * t[0]};
  const double white = accel_.noise_density / std::sqrt(timestep_);
  const double walk = accel_.bias_walk * std::sqrt(timestep_);
  for (int k = 0; k < 3; ++k) {
    if (walk > 0) accel_bias_[k] += walk * own_normal_.Next();
    accel_out[k] = a[k] - q[0] * t[k] + ut[k] + accel_bias_[k] +
                   (white > 0 ? white * own_normal_.Next() : 0.0);
  }
  std::memcpy(quat_out, seen.quat, sizeof(double) * 4);
  previous_truth_ = truth;
  previous_measured_ = measured;
}

}  // namespace mjf::realism
