// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The control stage's plugins, wired from the experiment: the interaction graph and desired
// formation handed to the formation law (checked here, so a bad topology or shape fails before
// any step), the leader's guidance, the formation law (central, per follower or per agent over
// the simulated network) and one attitude instance per vehicle. No MuJoCo: the model reaches the
// plugins only as the ABI's opaque pointer.
#ifndef MJFORMATION_CONTROL_CONTROL_WIRING_HPP_
#define MJFORMATION_CONTROL_CONTROL_WIRING_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <initializer_list>
#include <memory>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/control_tick.hpp"
#include "mjformation/control/plugin_host.hpp"

namespace mjf::formation {
class Graph;
class Shape;
}  // namespace mjf::formation

namespace mjf::runner {

// The plugin named in section `section`, which must be of one of `kinds`; otherwise a
// PluginError "FILE:LINE: [section] plugin: 'x' is a <kind> plugin; <need>".
const LoadedPlugin& FindPlugin(const PluginRegistry& registry, const ExperimentConfig& config,
                               const PluginSection& section, std::initializer_list<mjfKind> kinds,
                               const char* need);

// What the vehicles give the plugins: each one's info (owned by the caller's bindings, which
// must outlive the plugins) and start position, and the compiled model as the ABI's opaque type.
struct VehicleContexts {
  std::vector<const mjfVehicleInfo*> info;
  std::vector<std::array<double, 3>> initial_positions;
  const struct mjModel_* model = nullptr;
};

class ControlWiring {
 public:
  // Builds and checks the graph and the desired formation. Throws ConfigError.
  ControlWiring(const ExperimentConfig& config, const PluginRegistry& registry,
                VehicleContexts vehicles);
  ~ControlWiring();
  ControlWiring(const ControlWiring&) = delete;
  ControlWiring& operator=(const ControlWiring&) = delete;

  // Per-agent execution ([execution] mode = "per_agent"): the channel stage over the simulated
  // network; nullptr in central mode. Jacobi exchange is refused (or warned about) where it
  // diverges.
  std::unique_ptr<AgentChannel> MakeChannel() const;
  // Every plugin instance of the control tick. `channel` is MakeChannel()'s.
  ControlPlugins CreatePlugins(const LoadedPlugin& attitude, const AgentChannel* channel) const;
  // Before the first tick every vehicle holds its initial position at the altitude.
  std::vector<mjfSetpoint> InitialSetpoints() const;
  // What the controllers see: the [sensors] stage, and behind it, when [estimator]
  // names a plugin other than "passthrough", one estimator instance per vehicle.
  std::unique_ptr<SensorStage> MakeSensors() const;

  // The desired formation (nullptr when [formation.shape] type = "none").
  const formation::Shape* shape() const { return shape_.get(); }
  // Where each vehicle starts (the plugins' initial_pos points into these).
  const std::vector<std::array<double, 3>>& initial_positions() const {
    return vehicles_.initial_positions;
  }

 private:
  int n_vehicles() const { return static_cast<int>(vehicles_.info.size()); }
  int n_followers() const { return n_vehicles() - 1; }
  void BuildGraphAndShape();
  mjfCreateContext VehicleContext(const mjfCreateContext& base, int vehicle) const;
  const LoadedPlugin& FindAgentPlugin(const LoadedPlugin& named) const;
  std::vector<std::unique_ptr<PluginInstance>> CreateAgents(const LoadedPlugin& agent,
                                                            const mjfCreateContext& base,
                                                            const AgentChannel& channel) const;
  void RequireFormationInputs() const;
  // The graphs of [[topology.switch]], each checked like [topology]'s (Graph's validation).
  void BuildSwitchGraphs();
  // One instance of the formation law per switch, created now so that a refusal comes before
  // any step; refused unless the law is a central formation plugin.
  std::vector<FormationSwitch> CreateFormationSwitches(const LoadedPlugin& formation,
                                                       const mjfCreateContext& base,
                                                       const PluginSection& section) const;
  std::unique_ptr<PluginInstance> CreateFormation(const LoadedPlugin& formation,
                                                  const mjfCreateContext& base,
                                                  const PluginSection& section) const;
  // [formation] with accel_limit = "vehicle" replaced by the followers' smallest bound.
  PluginSection FormationSection(const LoadedPlugin& attitude) const;

  const ExperimentConfig& config_;
  const PluginRegistry& registry_;
  VehicleContexts vehicles_;
  // Handed to the plugins by pointer: they live as long as this object, which outlives them.
  std::unique_ptr<formation::Graph> graph_;
  std::unique_ptr<formation::Shape> shape_;
  mjfGraph abi_graph_{};
  mjfShape abi_shape_{};
  std::vector<int> edge_from_, edge_to_;
  std::vector<double> edge_weight_;
  // A later graph in the ABI's form; its arrays live as long as this object (as the first's).
  struct SwitchGraph {
    std::vector<double> leader_weight;
    std::vector<int> edge_from, edge_to;
    std::vector<double> edge_weight;
    mjfGraph abi{};
  };
  std::vector<std::unique_ptr<SwitchGraph>> switch_graphs_;  // [topology_switches]
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_CONTROL_WIRING_HPP_
