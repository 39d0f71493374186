// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation.swarm: flies every vehicle of an exported experiment (SwarmHost: the leader's
// guidance, the formation law, one attitude instance per vehicle). Its <config> keys are the
// experiment file's sections, each the body of a TOML inline table (swarm_host.hpp); the bodies
// `uav0_vehicle` (the leader) to `uavN_vehicle` reference the instance, under whatever names an
// attach gave them (attach_names.hpp). Timing, state and actuation: actuator_plugin.hpp.
#ifndef MJFORMATION_MUJOCO_PLUGIN_SWARM_PLUGIN_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_SWARM_PLUGIN_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <vector>

#include "actuator_plugin.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::native {

class SwarmPlugin {
 public:
  static constexpr char kName[] = "mjformation.swarm";
  // Registers the plugin with MuJoCo (its attributes: the carried sections).
  static void Register();

  // The callbacks' plugin-specific part (PluginKind):
  // a holder with a SwarmHost of the instance's configuration; the files it names and the
  // plugin libraries are read once per model (shared by every mjData, copy and reset).
  static std::unique_ptr<Holder> Make(const mjModel* m, int instance);
  // The held forces' and the tick's state size, while the model compiles (its sensors and actuators
  // are not there yet: the plugins are created on the vehicles' description alone). Checks every
  // section as the experiment parser does, and that the bodies referencing the instance are its
  // vehicles.
  static size_t StateSize(const mjModel* m, int instance);

  // The instance's configuration, read with the experiment file's parser; relative paths are
  // read against the scene's folder. Throws runner::ConfigError naming the instance.
  static runner::ExperimentConfig Config(const mjModel* m, int instance);
  // The vehicles' bodies as the exported scene names them (runner::VehiclePrefix), 0 = leader.
  static std::vector<std::string> Bodies(int followers);
  // How the swarm's names read in `m`: as exported, or renamed by an attach.
  static runner::SceneNames Names(const mjModel* m, int instance,
                                  const runner::ExperimentConfig& config);
};

extern const PluginKind kSwarmKind;

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_SWARM_PLUGIN_HPP_
