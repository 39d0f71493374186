// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/estimated_sensors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/realism/gaussian.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

using realism::Channel;

// The wander part common to every vehicle: one stream, the same in every vehicle's model.
constexpr uint64_t kCommonVehicle = 0xC0FFEE;

// The first part of `s` that is not finite ("position", ...), or null when all are.
const char* NonFinitePart(const mjfVehicleState& s) {
  const std::pair<const double*, const char*> parts[] = {
      {s.pos, "position"}, {s.vel, "velocity"}, {s.gyro, "body rate"}};
  for (const auto& [values, name] : parts) {
    if (!std::all_of(values, values + 3, [](double v) { return std::isfinite(v); })) return name;
  }
  if (!std::all_of(s.quat, s.quat + 4, [](double v) { return std::isfinite(v); })) {
    return "attitude";
  }
  return nullptr;
}

// The steps at which any aiding sample is taken are multiples of this: each channel samples the
// truth of steps 0, T, 2T, ... of its period T (SensorModel::StepChannel; every step without a
// rate), so both channels' steps are multiples of the greatest common divisor of their periods.
int64_t AidingPeriodSteps(const realism::SensorParams& p, double timestep) {
  int64_t period = 0;
  for (Channel c : {Channel::kPosition, Channel::kVelocity}) {
    const double rate = p[c].rate_hz;
    period = std::gcd(period, rate > 0 ? WholeSteps(1.0 / rate, timestep) : int64_t{1});
  }
  return period;
}

}  // namespace

mjfSensorInfo SuiteInfo(const realism::SensorParams& p, double timestep, double gravity) {
  mjfSensorInfo s{};
  s.has_accel = p.accel.enabled ? 1 : 0;
  s.accel_in_world = 0;
  // The attitude channel's white error e (std sigma per sample at its rate r) rotates the
  // specific force by e: an acceleration error g e, of density g sigma / sqrt(r); its bias walk
  // q gives an acceleration bias walking at g q.
  const realism::ChannelNoise& att = p[Channel::kAttitude];
  const double rate = att.rate_hz > 0 ? att.rate_hz : 1000.0;
  const double tilt_density = gravity * att.white_std / std::sqrt(rate);
  s.accel_noise_density = std::hypot(p.accel.noise_density, tilt_density);
  s.accel_bias_walk = std::hypot(p.accel.bias_walk, gravity * att.bias_walk);
  s.position_sources = MJF_MEASURES_POSITION | MJF_MEASURES_VELOCITY;
  s.max_latency = std::max(p[Channel::kPosition].latency_s, p[Channel::kVelocity].latency_s);
  s.position_wander_std = p[Channel::kPosition].wander_sigma;
  s.position_wander_tau = p[Channel::kPosition].wander_tau;
  s.aiding_period = static_cast<double>(AidingPeriodSteps(p, timestep)) * timestep;
  return s;
}

EstimatedSensors::EstimatedSensors(const ExperimentConfig& c, int n_vehicles, double gravity,
                                   const MakeEstimator& make)
    : timestep_(c.timestep),
      gravity_(gravity),
      suite_(SuiteInfo(c.sensors.params, c.timestep, gravity)),
      held_(n_vehicles),
      estimates_(n_vehicles),
      inputs_(n_vehicles),
      arrived_(n_vehicles),
      native_refusal_(NativeSensorRefusal(c)) {
  models_.reserve(n_vehicles);
  for (int i = 0; i < n_vehicles; ++i) {
    // Stream 1 as MeasuredSensors (same white noise and bias for the same seed); 2: this
    // vehicle's wander and accelerometer; the common wander from one shared stream.
    models_.emplace_back(c.sensors.params, c.timestep, realism::StreamSeed(c.seed, i, 1),
                         realism::StreamSeed(c.seed, i, 2),
                         realism::StreamSeed(c.seed, kCommonVehicle, 3));
    estimators_.push_back(make(i, suite_));
  }
}

void EstimatedSensors::Measure(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                               std::vector<mjfVehicleState>* measured) {
  // The sensor models of every vehicle, then every estimator plugin: four clock reads per step
  // (~100 ns against a step of tens of microseconds) time the two apart.
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < models_.size(); ++i) MeasureOne(static_cast<int>(i), step, time, truth[i]);
  const auto measured_at = std::chrono::steady_clock::now();
  for (size_t i = 0; i < models_.size(); ++i) {
    EstimateOne(static_cast<int>(i), step, time);
    (*measured)[i] = estimates_[i].state;
  }
  const auto end = std::chrono::steady_clock::now();
  sensor_model_seconds_ += std::chrono::duration<double>(measured_at - start).count();
  estimator_seconds_ += std::chrono::duration<double>(end - measured_at).count();
}

// What the sensors give this step: the held samples, the accelerometer over the step just
// ended, and the aiding samples that arrived (stamped with when they were taken), as the
// vehicle's estimator input.
void EstimatedSensors::MeasureOne(int vehicle, int64_t step, double time,
                                  const mjfVehicleState& truth) {
  realism::SensorModel& model = models_[vehicle];
  model.Measure(step, truth, &held_[vehicle]);
  mjfEstimatorInput& in = inputs_[vehicle];
  in = mjfEstimatorInput{};
  in.vehicle = vehicle;
  in.imu.time = time;
  in.imu.has_accel = suite_.has_accel;
  model.Accelerometer(step, truth, held_[vehicle], gravity_, in.imu.accel, in.imu.quat);
  std::copy(held_[vehicle].gyro, held_[vehicle].gyro + 3, in.imu.gyro);
  // Position and velocity samples taken at the same step travel as one measurement.
  std::vector<mjfMeasurement>& arrived = arrived_[vehicle];
  arrived.clear();
  for (const auto& f : model.fresh()) {
    if (arrived.empty() || NearestStep(arrived.back().time_taken, timestep_) != f.taken_step) {
      arrived.push_back(mjfMeasurement{});
      arrived.back().time_taken = static_cast<double>(f.taken_step) * timestep_;
    }
    mjfMeasurement& m = arrived.back();
    const bool pos = f.channel == Channel::kPosition;
    m.fields |= pos ? MJF_MEASURES_POSITION : MJF_MEASURES_VELOCITY;
    std::copy(f.value.begin(), f.value.end(), pos ? m.pos : m.vel);
    std::fill_n(pos ? m.pos_std : m.vel_std, 3, f.stated_std);
  }
  std::sort(arrived.begin(), arrived.end(),
            [](const auto& a, const auto& b) { return a.time_taken < b.time_taken; });
  in.n_measurements = static_cast<int>(arrived.size());
  in.measurements = arrived.data();
  in.held = &held_[vehicle];
}

void EstimatedSensors::EstimateOne(int vehicle, int64_t step, double time) {
  mjfStepContext ctx{};
  ctx.time = time;
  ctx.step = step;
  ctx.timestep = timestep_;
  ctx.n_vehicles = static_cast<int>(models_.size());
  ctx.error = error_.data();
  ctx.error_size = error_.size();
  ctx.estimator = &inputs_[vehicle];
  ctx.estimate = &estimates_[vehicle];
  error_[0] = '\0';
  PluginInstance& plugin = *estimators_[vehicle];
  const int code = plugin.Compute(ctx);
  if (code != 0) {
    error_.back() = '\0';
    throw SimulationError(
        fmt::format("t = {:.3f} s: estimator plugin '{}' (vehicle {}) failed "
                    "(code {}): {}",
                    time, plugin.descriptor().name, vehicle, code,
                    error_[0] ? error_.data() : "no reason given"));
  }
  // What the controllers get next: a non-finite estimate would end the run a step later under
  // another name (the vehicles' states and setpoints), so it stops here, naming its source.
  if (const char* part = NonFinitePart(estimates_[vehicle].state)) {
    throw SimulationError(fmt::format(
        "t = {:.3f} s: estimator plugin '{}' (vehicle {}) gave a non-finite {} estimate", time,
        plugin.descriptor().name, vehicle, part));
  }
}

void EstimatedSensors::VisitState(FixedStateArchive& archive) {
  archive(models_, held_, estimates_);
  // Each instance's declared state, of the fixed size it declared at create(), written and
  // read in place (the native MuJoCo plugin walks this every step).
  for (auto& estimator : estimators_) {
    archive.Block(
        estimator->state_size(), [&](double* out) { estimator->GetState(out); },
        [&](const double* in) { estimator->SetState(in); });
  }
}

void EstimatedSensors::RequireNativeState() const {
  if (!native_refusal_.empty()) throw SimulationError(native_refusal_);
  for (const auto& estimator : estimators_) {
    if (estimator->declares_state()) continue;
    throw SimulationError(std::string("[estimator] plugin '") + estimator->descriptor().name +
                          "' declares no state (plugin ABI 4: state_size, get_state, "
                          "set_state): its filter cannot be copied or checkpointed");
  }
}

}  // namespace mjf::runner
