// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The stages a control tick is made of, beyond the plugins: what the controllers see of the
// world (sensor stages) and what the world does to the vehicles besides their rotors (force
// stages). A new realism model (sensor noise, a communication channel, wind) is one new class
// implementing one of these interfaces, added in one place: MakeSensorStage / MakeForceStages
// in runner/control/src/stage_factory.cc. Stages know nothing of MuJoCo: they take and give plain
// arrays.
#ifndef MJFORMATION_CONTROL_STAGES_HPP_
#define MJFORMATION_CONTROL_STAGES_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/config/fixed_state_archive.hpp"
#include "mjformation/config/state_archive.hpp"

namespace mjf::runner {

struct ExperimentConfig;

// Truth in, what the controllers see out. Called once per physics step, before any plugin.
class SensorStage {
 public:
  virtual ~SensorStage() = default;
  // `measured` has the size of `truth`; step is the physics step index, time = step * dt.
  virtual void Measure(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                       std::vector<mjfVehicleState>* measured) = 0;
  // True when Measure keeps nothing from one call to the next (a tick's state then omits it).
  virtual bool stateless() const { return false; }
  // Everything Measure carries from one call to the next, both ways, in a length fixed at
  // construction (fixed_state_archive.hpp): part of the control tick's state, so of the native
  // MuJoCo plugin's plugin_state and of the runner's checkpoints. saves_state(): true when
  // VisitState walks all the stage keeps (a stateless stage has nothing to walk).
  virtual bool saves_state() const { return stateless(); }
  virtual void VisitState(FixedStateArchive& archive) { (void)archive; }
  // Throws SimulationError, naming the key, when the state is past what the native MuJoCo
  // plugin holds in plugin_state (the runner's own checkpoints take any length).
  virtual void RequireNativeState() const {}
};

// Perfect sensors: the controllers see the truth, bit for bit (the default).
class IdealSensors final : public SensorStage {
 public:
  void Measure(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
               std::vector<mjfVehicleState>* measured) override;
  bool stateless() const override { return true; }
};

// External forces on each vehicle (wind, drag, ...), applied at its centre of mass in the world
// frame. Called once per physics step after the controls are computed.
class ForceStage {
 public:
  virtual ~ForceStage() = default;
  // Adds this stage's force (N, world frame) to force[3 * i + k] for every vehicle i.
  virtual void AddForces(int64_t step, double time, const std::vector<mjfVehicleState>& truth,
                         std::vector<double>* force) = 0;
  // Checkpoints, as SensorStage's; the fixed-length walk is the native MuJoCo plugin's
  // plugin_state (fixed_state_archive.hpp).
  virtual bool saves_state() const { return false; }
  virtual void VisitState(StateArchive& archive) { (void)archive; }
  virtual void VisitState(FixedStateArchive& archive) { (void)archive; }
};

// A force stage that knows the wind at each vehicle (recorded with [wind] on).
class WindStage : public ForceStage {
 public:
  // m/s, world frame, per vehicle, as of the last AddForces (empty before it).
  virtual const std::vector<std::array<double, 3>>& wind() const = 0;
};

// The longest latency, in physics steps, whose buffer the native MuJoCo plugin holds in
// plugin_state: every step copies the whole state in and out, so the buffer is bounded.
constexpr int64_t kNativeLatencySteps = 1000;
// Why the native MuJoCo plugin cannot hold the sensor state of `config` (naming the [sensors]
// key and the number), or empty when it can.
std::string NativeSensorRefusal(const ExperimentConfig& config);

// The stages the experiment asks for (ideal sensors and no force stage by default).
std::unique_ptr<SensorStage> MakeSensorStage(const ExperimentConfig& config);
std::vector<std::unique_ptr<ForceStage>> MakeForceStages(const ExperimentConfig& config);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_STAGES_HPP_
