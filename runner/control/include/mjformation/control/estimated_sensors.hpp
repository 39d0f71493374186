// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The sensor stage with a state estimator behind it ([estimator] plugin other than
// "passthrough"): per vehicle, the sensor model measures (runner/realism), the accelerometer
// sample and the aiding samples that became available this step (stamped with the time they
// were taken) are handed to that vehicle's estimator plugin, and what the controllers see is its
// estimate. No MuJoCo: the simulation creates the plugin instances and hands them over.
#ifndef MJFORMATION_CONTROL_ESTIMATED_SENSORS_HPP_
#define MJFORMATION_CONTROL_ESTIMATED_SENSORS_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/control/plugin_host.hpp"
#include "mjformation/control/stages.hpp"
#include "mjformation/realism/sensor_model.hpp"

namespace mjf::runner {

struct ExperimentConfig;

// What an estimator plugin is told of the suite: the accelerometer's noise plus what the
// attitude channel's error adds to the rotated specific force (a tilt error e gives g e), the
// aiding channels, the largest latency and the steps at which aiding samples are taken.
mjfSensorInfo SuiteInfo(const realism::SensorParams& p, double timestep, double gravity);

class EstimatedSensors final : public SensorStage {
 public:
  // make(vehicle, suite) creates vehicle's estimator instance (throws PluginError).
  using MakeEstimator =
      std::function<std::unique_ptr<PluginInstance>(int vehicle, const mjfSensorInfo& suite)>;
  EstimatedSensors(const ExperimentConfig& c, int n_vehicles, double gravity,
                   const MakeEstimator& make);
  void Measure(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
               std::vector<mjfVehicleState>* measured) override;
  // The tick's state: the sensor models, the held samples and estimates (with their
  // covariance), and every estimator instance's ABI state (a plugin that declares none has
  // none; RequireNativeState refuses it).
  bool saves_state() const override { return true; }
  void VisitState(FixedStateArchive& archive) override;
  void RequireNativeState() const override;

  // Per vehicle, as of the last Measure: the estimate (with covariance) and the held samples.
  const std::vector<mjfEstimate>& estimates() const { return estimates_; }
  const std::vector<mjfVehicleState>& held() const { return held_; }
  const std::vector<std::unique_ptr<PluginInstance>>& estimators() const { return estimators_; }
  // Wall time spent in Measure so far, s: the sensor models (noise, latency, the accelerometer)
  // and the estimator plugins apart; `mjformation bench` reports each as a share of the flight.
  double sensor_model_seconds() const { return sensor_model_seconds_; }
  double estimator_seconds() const { return estimator_seconds_; }
  double wall_seconds() const { return sensor_model_seconds_ + estimator_seconds_; }

 private:
  void MeasureOne(int vehicle, int64_t step, double time, const mjfVehicleState& truth);
  void EstimateOne(int vehicle, int64_t step, double time);

  double timestep_, gravity_;
  mjfSensorInfo suite_{};
  std::vector<realism::SensorModel> models_;
  std::vector<std::unique_ptr<PluginInstance>> estimators_;
  std::vector<mjfVehicleState> held_;
  std::vector<mjfEstimate> estimates_;
  std::vector<mjfEstimatorInput> inputs_;             // per vehicle, rebuilt every step
  std::vector<std::vector<mjfMeasurement>> arrived_;  // per vehicle, reused every step
  std::array<char, 512> error_{};
  std::string native_refusal_;  // NativeSensorRefusal of the configuration
  double sensor_model_seconds_ = 0, estimator_seconds_ = 0;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_ESTIMATED_SENSORS_HPP_
