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

namespace mjf::native {

// The experiment sections a native instance carries, each as one MJCF <config> key whose value
// is the body of a TOML inline table (`radius = 20.0, omega = 0.157`).
const std::vector<std::string>& CarriedSections();

// Builds the experiment from an instance's <config> pairs with the experiment file's own parser,
// so names, defaults, validation and messages are those of the experiment file. `where` names
// the plugin and instance. Throws mjf::runner::ConfigError.
runner::ExperimentConfig ConfigFromPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs, const std::string& where);

class SwarmHost {
 public:
  SwarmHost(const mjModel* m, const runner::ExperimentConfig& config);
  ~SwarmHost();
  SwarmHost(const SwarmHost&) = delete;
  SwarmHost& operator=(const SwarmHost&) = delete;

  // Runs one control tick of our plugins for physics step `step` on the sensors of `d` and
  // writes each driven actuator's control into `controls` (indexed by actuator id).
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls);
  double timestep() const;
  // Builds every stage and plugin instance again, as at construction (mj_resetData).
  void Restart(const mjModel* m);

 private:
  void Build(const mjModel* m, const runner::ExperimentConfig& config);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_SWARM_HOST_HPP_
