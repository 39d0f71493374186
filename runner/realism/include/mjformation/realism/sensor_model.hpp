// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What one vehicle's controllers measure of its true state: per channel (position, velocity,
// attitude, body rate) white noise, a bias random walk, a sample rate with zero-order hold and a
// latency. Pure C++ (no MuJoCo): the runner calls Measure() once per physics step, between
// reading MuJoCo's sensors and the plugins. Seeded per vehicle; same seed, same bytes.
#ifndef MJFORMATION_REALISM_SENSOR_MODEL_HPP_
#define MJFORMATION_REALISM_SENSOR_MODEL_HPP_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mjformation/plugin.h"
#include "mjformation/realism/gaussian.hpp"

namespace mjf::realism {

// One channel's error model. Units are the channel's: m (position), m/s (velocity), rad
// (attitude: a small rotation applied to the true attitude, in body axes), rad/s (body rate).
struct ChannelNoise {
  double white_std = 0.0;  // standard deviation of the white noise added to each sample, per axis
  double bias_walk = 0.0;  // random-walk intensity of the bias, unit/sqrt(s): var(b(t)) = q^2 t
  double rate_hz = 0.0;    // samples per second, held in between; 0: every physics step
  double latency_s = 0.0;  // age of the truth a sample reports, s (a whole number of steps)
};

enum class Channel { kPosition = 0, kVelocity, kAttitude, kBodyRate };
constexpr int kChannels = 4;
const char* ChannelName(Channel c);  // "position", "velocity", "attitude", "body_rate"

struct SensorParams {
  std::array<ChannelNoise, kChannels> channel;

  ChannelNoise& operator[](Channel c) { return channel[static_cast<int>(c)]; }
  const ChannelNoise& operator[](Channel c) const { return channel[static_cast<int>(c)]; }

  // Exact pass-through: what the controllers see is the truth, bit for bit.
  static SensorParams Ideal();
  // A small UAV with a GNSS receiver, an attitude estimate and a MEMS gyro; sources in
  // sensor_model.cc and docs/REALISM.md.
  static SensorParams Typical();
  // White noise and bias walk multiplied by `factor` (rates and latencies unchanged).
  SensorParams Scaled(double factor) const;
  bool IsIdeal() const;
  // Empty when usable with this physics timestep, else "<channel>_<key>: reason".
  std::string Validate(double timestep) const;
};

class SensorModel {
 public:
  // Params must pass Validate(timestep) (throws std::invalid_argument otherwise).
  SensorModel(const SensorParams& params, double timestep, uint64_t seed);

  // The measurement at physics step `step` of the true state `truth`. Call once per step with
  // step = 0, 1, 2, ... (the latency buffer counts on it; throws std::logic_error otherwise).
  void Measure(int64_t step, const mjfVehicleState& truth, mjfVehicleState* measured);

  // The current bias of a channel (for tests and diagnostics).
  const std::array<double, 3>& Bias(Channel c) const { return channels_[static_cast<int>(c)].bias; }

 private:
  struct ChannelState {
    ChannelNoise noise;
    int dim = 3;                   // 4 for the attitude quaternion
    int64_t period_steps = 1;      // steps between samples
    int64_t latency_steps = 0;     // steps of delay
    std::vector<double> history;   // ring buffer of (latency + 1) truths, dim values each
    std::array<double, 4> held{};  // the last sample (dim values), true value + errors
    std::array<double, 3> bias{};  // current bias, per axis
    int64_t last_sample = -1;      // truth step of the held sample
    // Counters instead of step % n (integer division was most of a channel's cost per step).
    int64_t write_slot = 0;  // where this step's truth goes in history
    int64_t phase = 0;       // steps since the last sample, once the delay has passed
    // The bias walks every `bias_every` samples (at least every 10 ms: a drift that matters over
    // seconds need not cost three normal draws per 1 kHz gyro sample); var(b) = q^2 t at those
    // times, held in between.
    int64_t bias_every = 1, bias_count = 0;
  };
  void StepChannel(ChannelState& ch, int64_t step, const double* truth);

  bool ideal_;
  double timestep_;
  Gaussian normal_;
  std::array<ChannelState, kChannels> channels_;
  int64_t next_step_ = 0;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_SENSOR_MODEL_HPP_
