// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/control_setup.hpp"

#include <string>
#include <utility>

#include "mjformation/config/source_location.hpp"
#include "mjformation/control/agent_channel.hpp"

namespace mjf::runner {
namespace {

// A rotor layout the attitude plugin refuses is a property of the model and its [vehicles]
// rotors mapping, not of [attitude]: the refusal is pointed there, with the model's own rotor
// names in place of the plugin's rotor<k>.
ControlPlugins CreatePluginsNamingRotors(const ControlWiring& wiring,
                                         const ExperimentConfig& config,
                                         const LoadedPlugin& attitude, AgentChannel* channel) {
  try {
    return wiring.CreatePlugins(attitude, channel);
  } catch (const PluginError& e) {
    std::string text = e.what();
    const size_t at = text.find("refused its configuration: the rotor");
    if (config.vehicle_rotors.empty() || at == std::string::npos) throw;
    std::string reason = text.substr(text.find(": the rotor", at) + 2);
    for (size_t k = 0; k < config.vehicle_rotors.size(); ++k) {
      const std::string plugin_name = "rotor" + std::to_string(k) + " (";
      const std::string model_name =
          "'" + config.vehicle_rotors[k] + "' (rotor" + std::to_string(k) + ", ";
      for (size_t p = 0; (p = reason.find(plugin_name, p)) != std::string::npos;
           p += model_name.size()) {
        reason.replace(p, plugin_name.size(), model_name);
      }
    }
    throw PluginError(OriginLocation(config.source_path, config.vehicle_rotors_origin,
                                     SectionKey("vehicles", "rotors"))
                          .Prefix() +
                      ": the attitude plugin '" + config.attitude.plugin +
                      "' cannot fly this rotor layout: " + reason);
  }
}

}  // namespace

const LoadedPlugin& LoadAttitudePlugin(const PluginRegistry& registry,
                                       const ExperimentConfig& config) {
  const LoadedPlugin& attitude = FindPlugin(registry, config, config.attitude, {MJF_KIND_ATTITUDE},
                                            "this section needs an attitude plugin");
  ResolveAttributes(*attitude.descriptor, config.attitude, config.source_path);
  return attitude;
}

ControlSetup SetUpControl(const ExperimentConfig& config, const PluginRegistry& registry,
                          const LoadedPlugin& attitude, VehicleContexts vehicles,
                          int actuators_per_vehicle) {
  ControlSetup setup;
  setup.wiring = std::make_unique<ControlWiring>(config, registry, std::move(vehicles));
  std::unique_ptr<AgentChannel> channel = setup.wiring->MakeChannel();  // per-agent execution
  ControlPlugins plugins =
      CreatePluginsNamingRotors(*setup.wiring, config, attitude, channel.get());
  setup.tick = std::make_unique<ControlTick>(
      std::move(plugins), setup.wiring->MakeSensors(), setup.wiring->InitialSetpoints(),
      actuators_per_vehicle, config.altitude, config.timestep, std::move(channel));
  return setup;
}

}  // namespace mjf::runner
