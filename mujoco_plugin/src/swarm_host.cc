// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "swarm_host.hpp"

#include <sstream>
#include <stdexcept>

#include "mjformation/config/config.hpp"
#include "mjformation/config/paths.hpp"
#include "mjformation/control/control_tick.hpp"
#include "mjformation/control/control_wiring.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::native {

const std::vector<std::string>& CarriedSections() {
  static const std::vector<std::string> kSections = {"run",    "vehicles",  "topology",
                                                     "leader", "formation", "attitude"};
  return kSections;
}

// The runner names a file and line ("WHERE:3: [formation] q: ..."); the lines of the text built
// above mean nothing to the MJCF's author, the section and key say it all.
std::string WithoutLine(const std::string& message, const std::string& where) {
  std::string out = message;
  for (size_t at = out.find(where + ":"); at != std::string::npos;
       at = out.find(where + ":", at + 1)) {
    size_t digits = at + where.size() + 1;
    size_t end = digits;
    // ":LINE" or ":LINE:COLUMN"
    while (end < out.size() && ((out[end] >= '0' && out[end] <= '9') ||
                                (out[end] == ':' && end + 1 < out.size() && out[end + 1] != ' '))) {
      ++end;
    }
    if (end > digits) out.erase(at + where.size(), end - at - where.size());
  }
  return out;
}

runner::ExperimentConfig ConfigFromPairs(
    const std::vector<std::pair<std::string, std::string>>& pairs, const std::string& where) {
  // Each section becomes `section = { ... }`: the runner's parser then checks every name and
  // value and words its messages as it does for an experiment file.
  std::ostringstream toml;
  for (const auto& [key, value] : pairs) {
    if (!value.empty()) toml << key << " = {" << value << "}\n";
  }
  try {
    return runner::ParseExperiment(toml.str(), where);
  } catch (const runner::ConfigError& e) {
    std::string message = WithoutLine(e.what(), where);
    // A syntax error: name the <config> key whose value does not parse on its own.
    if (message.find("TOML syntax error") != std::string::npos) {
      for (const auto& [key, value] : pairs) {
        try {
          runner::ParseExperiment(key + " = {" + value + "}\n", where);
        } catch (const runner::ConfigError& alone) {
          if (std::string(alone.what()).find("TOML syntax error") == std::string::npos) continue;
          message = where + ": <config key=\"" + key +
                    "\">: " + message.substr(message.find("TOML syntax error"));
          break;
        }
      }
    }
    throw runner::ConfigError(message);
  }
}

struct SwarmHost::Impl {
  runner::ExperimentConfig config;
  std::unique_ptr<runner::PluginRegistry> registry;
  runner::VehicleBindings bindings;
  std::unique_ptr<runner::ControlWiring> wiring;
  std::unique_ptr<runner::ControlTick> tick;
  std::vector<mjfVehicleState> truth;
};

// The same construction as the runner's Simulation, on the scene MuJoCo compiled: the bindings
// read the vehicle model of [vehicles] model for mass, inertia and actuator geometry.
SwarmHost::SwarmHost(const mjModel* m, const runner::ExperimentConfig& config) {
  try {
    Build(m, config);
  } catch (const std::exception& e) {
    throw std::runtime_error(WithoutLine(e.what(), config.source_path));
  }
}

void SwarmHost::Restart(const mjModel* m) {
  const runner::ExperimentConfig config = impl_->config;
  impl_.reset();  // plugin instances before their libraries, as the runner ends them
  Build(m, config);
}

void SwarmHost::Build(const mjModel* m, const runner::ExperimentConfig& config) {
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  s.config = config;
  s.config.timestep = m->opt.timestep;
  s.registry =
      std::make_unique<runner::PluginRegistry>(runner::PluginSearchPath(s.config.plugin_path));
  const runner::LoadedPlugin& attitude =
      runner::FindPlugin(*s.registry, s.config, s.config.attitude, {MJF_KIND_ATTITUDE},
                         "this section needs an attitude plugin");
  runner::ResolveAttributes(*attitude.descriptor, s.config.attitude, s.config.source_path);
  std::vector<std::array<double, 3>> initial = runner::InitialPositions(s.config);
  s.bindings = runner::BindVehicles(m, s.config, *attitude.descriptor);
  s.truth.resize(s.config.followers + 1);
  runner::VehicleContexts contexts;
  for (const runner::VehicleBinding& b : s.bindings.vehicles) contexts.info.push_back(&b.info);
  contexts.initial_positions = std::move(initial);
  contexts.model = reinterpret_cast<const struct mjModel_*>(m);
  s.wiring = std::make_unique<runner::ControlWiring>(s.config, *s.registry, std::move(contexts));
  std::unique_ptr<runner::AgentChannel> channel = s.wiring->MakeChannel();
  runner::ControlPlugins plugins = s.wiring->CreatePlugins(attitude, channel.get());
  s.tick = std::make_unique<runner::ControlTick>(
      std::move(plugins), s.wiring->MakeSensors(), s.wiring->InitialSetpoints(),
      s.bindings.actuators_per_vehicle, s.config.altitude, s.config.timestep, std::move(channel));
}

SwarmHost::~SwarmHost() = default;

double SwarmHost::timestep() const { return impl_->config.timestep; }

void SwarmHost::Tick(int64_t step, const mjModel* m, const mjData* d, double* controls) {
  Impl& s = *impl_;
  runner::ReadTrueStates(d, s.bindings, &s.truth);
  s.tick->Run(step, s.truth, reinterpret_cast<const struct mjModel_*>(m),
              reinterpret_cast<const struct mjData_*>(d));
  const std::vector<double>& c = s.tick->controls();
  const int per = s.bindings.actuators_per_vehicle;
  for (size_t i = 0; i < s.bindings.vehicles.size(); ++i) {
    const std::vector<int>& ids = s.bindings.vehicles[i].actuators;
    for (int k = 0; k < per; ++k) controls[ids[k]] = c[i * per + k];
  }
}

}  // namespace mjf::native
