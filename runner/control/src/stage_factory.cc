// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one place where the experiment's realism settings become stages of the control tick:
// [sensors] -> MeasuredSensors (or IdealSensors), [wind] -> WindDrag (or no force stage).
#include <fmt/format.h>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/control/stages.hpp"
#include "mjformation/realism/gaussian.hpp"
#include "mjformation/realism/sensor_model.hpp"
#include "mjformation/realism/wind_field.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {

void IdealSensors::Measure(int64_t, double, const std::vector<mjfVehicleState>& truth,
                           std::vector<mjfVehicleState>* measured) {
  *measured = truth;
}

namespace {

// [sensors]: one seeded sensor model per vehicle (white noise, bias walk, rate hold, latency).
class MeasuredSensors final : public SensorStage {
 public:
  MeasuredSensors(const ExperimentConfig& c, int n_vehicles)
      : native_refusal_(NativeSensorRefusal(c)) {
    models_.reserve(n_vehicles);
    for (int i = 0; i < n_vehicles; ++i) {
      models_.emplace_back(c.sensors.params, c.timestep,
                           realism::StreamSeed(c.seed, i, /*stream=*/1));
    }
  }
  void Measure(int64_t step, double, const std::vector<mjfVehicleState>& truth,
               std::vector<mjfVehicleState>* measured) override {
    for (size_t i = 0; i < models_.size(); ++i) models_[i].Measure(step, truth[i], &(*measured)[i]);
  }
  bool saves_state() const override { return true; }
  void VisitState(FixedStateArchive& archive) override { archive(models_); }
  void RequireNativeState() const override {
    if (!native_refusal_.empty()) throw SimulationError(native_refusal_);
  }

 private:
  std::vector<realism::SensorModel> models_;
  std::string native_refusal_;
};

// [wind]: the wind at each vehicle (mean + Dryden turbulence + gusts) and the drag it causes,
// from the vehicle's true velocity, at its centre of mass.
class WindDrag final : public WindStage {
 public:
  WindDrag(const ExperimentConfig& c, int n_vehicles)
      : drag_(c.wind.drag), field_(c.wind.params, n_vehicles, c.timestep, c.seed) {}
  void AddForces(int64_t step, double, const std::vector<mjfVehicleState>& truth,
                 std::vector<double>* force) override {
    wind_ = &field_.Update(step);
    for (size_t i = 0; i < truth.size(); ++i) {
      const auto f = drag_.Force(truth[i].vel, (*wind_)[i].data());
      for (int k = 0; k < 3; ++k) (*force)[3 * i + k] += f[k];
    }
  }
  bool saves_state() const override { return true; }
  void VisitState(StateArchive& archive) override { archive(field_); }
  void VisitState(FixedStateArchive& archive) override { archive(field_); }
  const std::vector<std::array<double, 3>>& wind() const override {
    static const std::vector<std::array<double, 3>> kCalm;
    return wind_ ? *wind_ : kCalm;
  }

 private:
  realism::DragParams drag_;
  realism::WindField field_;
  const std::vector<std::array<double, 3>>* wind_ = nullptr;
};

}  // namespace

std::string NativeSensorRefusal(const ExperimentConfig& c) {
  for (int k = 0; k < realism::kChannels; ++k) {
    const double latency = c.sensors.params.channel[k].latency_s;
    const int64_t steps = WholeSteps(latency, c.timestep);
    if (steps <= kNativeLatencySteps) continue;
    return fmt::format(
        "[sensors] {}_latency = {} s is {} physics steps of delay; the native MuJoCo plugin "
        "holds at most {} (its latency buffer is part of plugin_state, copied every step): "
        "shorten it or fly the experiment with `mjformation run`",
        realism::ChannelName(static_cast<realism::Channel>(k)), latency, steps,
        kNativeLatencySteps);
  }
  return "";
}

std::unique_ptr<SensorStage> MakeSensorStage(const ExperimentConfig& c) {
  if (c.sensors.enabled()) return std::make_unique<MeasuredSensors>(c, c.followers + 1);
  return std::make_unique<IdealSensors>();
}

std::vector<std::unique_ptr<ForceStage>> MakeForceStages(const ExperimentConfig& c) {
  std::vector<std::unique_ptr<ForceStage>> stages;
  if (c.wind.enabled()) stages.push_back(std::make_unique<WindDrag>(c, c.followers + 1));
  return stages;
}

}  // namespace mjf::runner
