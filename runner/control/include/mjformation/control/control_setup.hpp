// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The one recipe that sets up an experiment's control stage, followed by both faces of the
// controllers: the runner's Simulation and the native MuJoCo plugin's SwarmHost. Same plugins,
// same order of creation, same refusals with the same words. No MuJoCo: the vehicles reach it
// as the plugin ABI's descriptions (VehicleContexts).
#ifndef MJFORMATION_CONTROL_CONTROL_SETUP_HPP_
#define MJFORMATION_CONTROL_CONTROL_SETUP_HPP_

#include <memory>

#include "mjformation/config/experiment.hpp"
#include "mjformation/control/control_tick.hpp"
#include "mjformation/control/control_wiring.hpp"
#include "mjformation/control/plugin_host.hpp"

namespace mjf::runner {

// The attitude plugin [attitude] names, its attributes resolved against its descriptor: what is
// wrong with it is said before any scene is compiled. Throws PluginError / ConfigError.
const LoadedPlugin& LoadAttitudePlugin(const PluginRegistry& registry,
                                       const ExperimentConfig& config);

// The wiring and the tick it feeds. The wiring owns what the plugins point into (graph, shape,
// start positions): it must outlive the tick.
struct ControlSetup {
  std::unique_ptr<ControlWiring> wiring;
  std::unique_ptr<ControlTick> tick;
};

// Wires the experiment's plugins over `vehicles` (their info must outlive the tick), creates
// every instance (a rotor layout the attitude plugin refuses is pointed at [vehicles] rotors
// when the model's rotors are mapped there, with the model's rotor names) and the tick with
// `actuators_per_vehicle` controls a vehicle. Throws ConfigError / PluginError.
ControlSetup SetUpControl(const ExperimentConfig& config, const PluginRegistry& registry,
                          const LoadedPlugin& attitude, VehicleContexts vehicles,
                          int actuators_per_vehicle);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_CONTROL_SETUP_HPP_
