// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The bridge between MuJoCo's engine plugins and our own plugin ABI: one SwarmHost flies a
// composed scene's vehicles with the same stages the runner builds (leader guidance, formation
// law, one attitude instance per vehicle, all loaded by name from our plugin search path), so
// the control maths has one implementation. It knows MuJoCo only to read sensors by name.
#ifndef MJFORMATION_MUJOCO_PLUGIN_SWARM_HOST_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_SWARM_HOST_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/export/carried_sections.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::runner {
class Actuation;
}

namespace mjf::native {

// The experiment sections a native instance carries, each as one MJCF <config> key whose value
// is the body of a TOML inline table (`radius = 20.0, omega = 0.157`): export's list.
using runner::CarriedSections;

// Builds the experiment from an instance's <config> pairs with the experiment file's own parser,
// so names, defaults, validation and messages are those of the experiment file. `where` names
// the plugin and instance; the relative paths of the values are read against `folder`, the
// scene's folder (SceneFolder; "" reads them as given). Throws mjf::runner::ConfigError.
runner::ExperimentConfig ConfigFromPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs, const std::string& where,
    const std::string& folder = "");

// `message` without the line numbers after `where` ("WHERE:3: [formation] q: ..." becomes
// "WHERE: [formation] q: ..."): the lines of text a host built mean nothing to the MJCF's author.
std::string WithoutLine(const std::string& message, const std::string& where);

// What every SwarmHost of one model shares, read once: the configuration, the plugin
// libraries and the vehicles' bindings (the vehicle file is read here, never per mjData).
struct SwarmShared;

class SwarmHost {
 public:
  // Reads the files and loads the libraries `config` names. bind_model: bind the vehicles'
  // sensors and actuators in `m` (false while the model compiles, when only the state's size
  // is wanted), whose names read `names` (attach_names.hpp). Throws std::runtime_error naming
  // the section.
  static std::shared_ptr<const SwarmShared> Prepare(const mjModel* m,
                                                    const runner::ExperimentConfig& config,
                                                    bool bind_model,
                                                    const runner::SceneNames& names = {});
  // Creates every stage and plugin instance, as the runner's Simulation does. Checks that the
  // tick's state can be saved (runner::ControlTick::RequireSavable).
  explicit SwarmHost(std::shared_ptr<const SwarmShared> shared);
  ~SwarmHost();
  SwarmHost(const SwarmHost&) = delete;
  SwarmHost& operator=(const SwarmHost&) = delete;

  // Runs one control tick of our plugins for physics step `step` on the sensors of `d` and
  // writes each driven actuator's control into `controls` (indexed by actuator id), and what
  // the step's forces are made of into `held` (held_size() doubles, below).
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls, double* held);
  // The forces the runner adds besides MuJoCo's actuators ([wind]'s drag, [vehicles]
  // rotor_model = "wrench"'s rotor wrenches), as a block of plugin_state beside the tick's
  // state, read at every evaluation of a step: [the tick's controls, [vehicle][rotor]] and [the
  // motor lags, likewise] with the wrench model, then [each vehicle's wind force, N, world
  // frame] with [wind]. Zeros are the state before the first step (motor lags at rest). Empty
  // when neither is on.
  size_t held_size() const;
  // Adds the step's forces into d->qfrc_passive (at each vehicle's centre of mass, as the
  // runner adds them after mj_step1: rotor wrenches, then the wind), from `held` and the
  // position stage of `d`.
  void AddForces(const mjModel* m, mjData* d, const double* held);
  // After the step's integration: the motor lags follow the tick's controls (the runner's
  // Actuation::Advance after mj_step2).
  void Advance(const mjModel* m, double* held);
  // The tick's state (runner::ControlTick::GetState), then the force stages' (the wind field's
  // Dryden filters, held samples and random streams): fixed size, every number a tick leaves
  // for the next.
  size_t state_size() const;
  void GetState(double* out) const;
  // GetState into the block it last got or set (ControlTick::UpdateState).
  void UpdateState(double* block) const;
  void SetState(const double* in);

 private:
  // The wrench rotor model on `m`, loaded with the motor lags of `held` (its controls copied
  // into the scratch the actuation takes).
  runner::Actuation& Wrench(const mjModel* m, const double* held);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_SWARM_HOST_HPP_
