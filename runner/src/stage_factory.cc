// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one place where the experiment's realism settings become stages of the control tick.
#include "mjformation/runner/config.hpp"
#include "mjformation/runner/stages.hpp"

namespace mjf::runner {

void IdealSensors::Measure(int64_t, double, const std::vector<mjfVehicleState>& truth,
                           std::vector<mjfVehicleState>* measured) {
  *measured = truth;
}

std::unique_ptr<SensorStage> MakeSensorStage(const ExperimentConfig&) {
  return std::make_unique<IdealSensors>();
}

std::vector<std::unique_ptr<ForceStage>> MakeForceStages(const ExperimentConfig&) { return {}; }

}  // namespace mjf::runner
