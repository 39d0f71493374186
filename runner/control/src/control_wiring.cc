// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/control_wiring.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "mjformation/config/shape_config.hpp"
#include "mjformation/config/source_location.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/control/estimated_sensors.hpp"
#include "mjformation/control/vehicle_accel_limit.hpp"
#include "mjformation/formation/graph.hpp"
#include "mjformation/formation/shape.hpp"
#include "mjformation/plugin_contract.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Where(const ExperimentConfig& c, const PluginSection& s) {
  return OriginLocation(c.source_path, {s.line, s.origin}, SectionKey(s.section)).Prefix();
}

}  // namespace

const LoadedPlugin& FindPlugin(const PluginRegistry& registry, const ExperimentConfig& c,
                               const PluginSection& s, std::initializer_list<mjfKind> kinds,
                               const char* need) {
  const LoadedPlugin& p = registry.Find(s.plugin, Where(c, s) + " plugin");
  for (mjfKind k : kinds) {
    if (p.descriptor->kind == k) return p;
  }
  const std::string kind = KindName(p.descriptor->kind);
  const bool vowel = std::string("aeiou").find(kind[0]) != std::string::npos;
  throw PluginError(Where(c, s) + " plugin: '" + s.plugin + "' is " + (vowel ? "an " : "a ") +
                    kind + " plugin; " + need);
}

ControlWiring::ControlWiring(const ExperimentConfig& config, const PluginRegistry& registry,
                             VehicleContexts vehicles)
    : config_(config), registry_(registry), vehicles_(std::move(vehicles)) {
  BuildGraphAndShape();
  BuildSwitchGraphs();
}

void ControlWiring::BuildSwitchGraphs() {
  for (const ExperimentConfig::TopologySwitch& sw : config_.topology_switches) {
    auto g = std::make_unique<SwitchGraph>();
    g->leader_weight = sw.leader_weight;
    std::vector<formation::Edge> edges;
    for (const auto& e : sw.edges) {
      g->edge_from.push_back(e.from);
      g->edge_to.push_back(e.to);
      g->edge_weight.push_back(e.weight);
      edges.push_back({e.from, e.to, e.weight});
    }
    try {
      formation::Graph(config_.followers, sw.leader_weight, edges).RequireSpanningTree();
    } catch (const std::invalid_argument& e) {
      SourceLocation{config_.source_path, sw.line, SectionKey("topology", "switch")}.Fail(e.what());
    }
    g->abi = {config_.followers,   g->leader_weight.data(), static_cast<int>(g->edge_from.size()),
              g->edge_from.data(), g->edge_to.data(),       g->edge_weight.data()};
    switch_graphs_.push_back(std::move(g));
  }
}

ControlWiring::~ControlWiring() = default;

// Graph and shape: checked here so a bad topology fails before any step.
void ControlWiring::BuildGraphAndShape() {
  for (const auto& e : config_.edges) {
    edge_from_.push_back(e.from);
    edge_to_.push_back(e.to);
    edge_weight_.push_back(e.weight);
  }
  try {
    std::vector<formation::Edge> edges;
    for (const auto& e : config_.edges) edges.push_back({e.from, e.to, e.weight});
    graph_ = std::make_unique<formation::Graph>(config_.followers, config_.leader_weight, edges);
  } catch (const std::invalid_argument& e) {
    SourceLocation{config_.source_path, 0, SectionKey("topology")}.Fail(e.what());
  }
  abi_graph_ = {config_.followers,
                config_.leader_weight.data(),
                static_cast<int>(edge_from_.size()),
                edge_from_.data(),
                edge_to_.data(),
                edge_weight_.data()};
  shape_ = MakeShape(config_);
  if (shape_) abi_shape_ = formation::ToAbi(*shape_);
}

std::unique_ptr<SensorStage> ControlWiring::MakeSensors() const {
  // "passthrough" is today's stage itself: the held samples, bit for bit, no plugin call. It
  // declares no attributes, so any key given is refused as the host refuses a plugin's unknown
  // keys (else `gate_sigma` in an [estimator] that names no plugin would be dropped unread).
  if (config_.estimator.plugin == "passthrough") {
    mjfPlugin passthrough{};
    passthrough.name = "passthrough";
    ResolveAttributes(passthrough, config_.estimator, config_.source_path);
    return MakeSensorStage(config_);
  }
  const LoadedPlugin& estimator =
      FindPlugin(registry_, config_, config_.estimator, {MJF_KIND_ESTIMATOR},
                 "this section needs an estimator plugin (e.g. kf_ins, passthrough)");
  mjfCreateContext base{};
  base.timestep = config_.timestep;
  base.n_vehicles = n_vehicles();
  base.model = vehicles_.model;
  const double gravity = vehicles_.info[0] ? vehicles_.info[0]->gravity : 9.81;
  return std::make_unique<EstimatedSensors>(
      config_, n_vehicles(), gravity, [&](int vehicle, const mjfSensorInfo& suite) {
        mjfCreateContext ctx = VehicleContext(base, vehicle);
        ctx.sensors = &suite;
        return std::make_unique<PluginInstance>(estimator, config_.estimator, config_.source_path,
                                                ctx);
      });
}

mjfCreateContext ControlWiring::VehicleContext(const mjfCreateContext& base, int vehicle) const {
  mjfCreateContext ctx = base;
  ctx.vehicle = vehicle;
  ctx.vehicle_info = vehicles_.info[vehicle];
  ctx.initial_pos = vehicles_.initial_positions[vehicle].data();
  return ctx;
}

// Per-agent execution ([execution] mode = "per_agent"): the channel stage over the simulated
// network. Jacobi exchange is refused (or warned about) where it diverges.
std::unique_ptr<AgentChannel> ControlWiring::MakeChannel() const {
  if (config_.network.execution != Execution::kPerAgent) return nullptr;
  auto channel =
      std::make_unique<AgentChannel>(*graph_, config_.network, config_.timestep, config_.seed);
  const double rho = channel->jacobi_spectral_radius();
  if (config_.network.coupling != Coupling::kJacobi) return channel;
  // Exact (dense eigenvalues) up to 400 followers; above, a power-iteration estimate that
  // cannot resolve rho from 1 on long rings (rho < 1 holds whenever L_H has a spanning tree).
  const bool exact = n_followers() <= 400;
  if (!(rho < 1.0)) {
    const std::string what = fmt::format(
        "{}: [execution] coupling: Jacobi exchange {} on this graph: the spectral radius of "
        "(D + H)^-1 A is {:.9f}{}",
        config_.source_path, exact ? "diverges" : "may not converge", rho,
        exact ? " >= 1" : " (power-iteration estimate, not resolved from 1)");
    if (exact && config_.network.refuse_divergent) {
      throw ConfigError(what + " (set jacobi_divergence = \"warn\" to run it anyway)");
    }
    std::fprintf(stderr, "warning: %s\n", what.c_str());
  } else if (std::pow(rho, config_.network.jacobi_rounds) > 0.9) {
    std::fprintf(stderr,
                 "warning: %s: [execution] jacobi_rounds = %d reduces the coupling error by less "
                 "than 10 %% per sample (spectral radius %.6f)\n",
                 config_.source_path.c_str(), config_.network.jacobi_rounds, rho);
  }
  return channel;
}

// The per-agent plugin for section [formation]: the named one if it is per-agent, else
// "<name>_agent" (so that --set execution.mode="per_agent" switches an experiment over).
const LoadedPlugin& ControlWiring::FindAgentPlugin(const LoadedPlugin& named) const {
  if (named.descriptor->kind == MJF_KIND_FORMATION_AGENT) return named;
  const std::string agent_name = plugin::contract::AgentName(config_.formation.plugin);
  for (const LoadedPlugin& p : registry_.plugins()) {
    if (p.descriptor->name == agent_name && p.descriptor->kind == MJF_KIND_FORMATION_AGENT) {
      return p;
    }
  }
  throw PluginError(Where(config_, config_.formation) + " plugin: '" + config_.formation.plugin +
                    "' has no per-agent version ('" + agent_name +
                    "') for [execution] mode = \"per_agent\"");
}

ControlPlugins ControlWiring::CreatePlugins(const LoadedPlugin& attitude,
                                            const AgentChannel* channel) const {
  mjfCreateContext base{};
  base.timestep = config_.timestep;
  base.n_vehicles = n_vehicles();
  base.model = vehicles_.model;
  ControlPlugins plugins;
  const LoadedPlugin& leader =
      FindPlugin(registry_, config_, config_.leader, {MJF_KIND_GUIDANCE},
                 "the leader needs a guidance plugin (e.g. circle, hover)");
  plugins.leader = std::make_unique<PluginInstance>(leader, config_.leader, config_.source_path,
                                                    VehicleContext(base, 0));
  const LoadedPlugin& formation =
      FindPlugin(registry_, config_, config_.formation,
                 {MJF_KIND_FORMATION, MJF_KIND_GUIDANCE, MJF_KIND_FORMATION_AGENT},
                 "followers need a formation, per-agent formation or guidance plugin");
  if (!config_.topology_switches.empty() &&
      (channel || formation.descriptor->kind != MJF_KIND_FORMATION)) {
    SourceLocation{config_.source_path, config_.topology_switches[0].line,
                   SectionKey("topology", "switch")}
        .Fail(
            "a switching topology needs a formation law run centrally (a formation plugin, "
            "[execution] mode = \"central\"); '" +
            config_.formation.plugin + "' here is not (the network's links are fixed for the run)");
  }
  if (channel) {
    plugins.formation_agents = CreateAgents(FindAgentPlugin(formation), base, *channel);
  } else if (formation.descriptor->kind == MJF_KIND_FORMATION_AGENT) {
    throw ConfigError(Where(config_, config_.formation) + " plugin: '" + config_.formation.plugin +
                      "' runs one instance per follower: it needs [execution] mode = "
                      "\"per_agent\"");
  } else if (formation.descriptor->kind == MJF_KIND_FORMATION) {
    const PluginSection section = FormationSection(attitude);
    plugins.formation = CreateFormation(formation, base, section);
    plugins.formation_switches = CreateFormationSwitches(formation, base, section);
  } else {
    // A guidance plugin per follower (e.g. hover): flies the vehicles without a formation law.
    for (int i = 1; i < n_vehicles(); ++i) {
      plugins.follower_guidance.push_back(std::make_unique<PluginInstance>(
          formation, config_.formation, config_.source_path, VehicleContext(base, i)));
    }
  }
  for (int i = 0; i < n_vehicles(); ++i) {
    plugins.attitude.push_back(std::make_unique<PluginInstance>(
        attitude, config_.attitude, config_.source_path, VehicleContext(base, i)));
  }
  return plugins;
}

std::unique_ptr<PluginInstance> ControlWiring::CreateFormation(const LoadedPlugin& formation,
                                                               const mjfCreateContext& base,
                                                               const PluginSection& section) const {
  RequireFormationInputs();
  mjfCreateContext ctx = base;
  ctx.vehicle = -1;
  ctx.graph = &abi_graph_;
  ctx.shape = &abi_shape_;
  return std::make_unique<PluginInstance>(formation, section, config_.source_path, ctx);
}

std::vector<FormationSwitch> ControlWiring::CreateFormationSwitches(
    const LoadedPlugin& formation, const mjfCreateContext& base,
    const PluginSection& section) const {
  std::vector<FormationSwitch> switches;
  for (size_t k = 0; k < switch_graphs_.size(); ++k) {
    const ExperimentConfig::TopologySwitch& sw = config_.topology_switches[k];
    mjfCreateContext ctx = base;
    ctx.vehicle = -1;
    ctx.graph = &switch_graphs_[k]->abi;
    ctx.shape = &abi_shape_;
    FormationSwitch one;
    // The first tick at or after `at` (a tick's time is step * timestep).
    one.step = static_cast<int64_t>(std::ceil(sw.at / config_.timestep - 1e-9));
    one.instance = std::make_unique<PluginInstance>(formation, section, config_.source_path, ctx);
    if (!one.instance->declares_state()) {
      std::fprintf(stderr,
                   "warning: %s:%d: [topology] switch: plugin '%s' declares no state: it starts "
                   "afresh at the switch (only its graph should change)\n",
                   config_.source_path.c_str(), sw.line, config_.formation.plugin.c_str());
    }
    switches.push_back(std::move(one));
  }
  return switches;
}

PluginSection ControlWiring::FormationSection(const LoadedPlugin& attitude) const {
  PluginSection section = config_.formation;
  namespace contract = plugin::contract;
  auto limit = section.attributes.find(contract::kAccelLimit);
  if (limit == section.attributes.end() || limit->second.text != contract::kFromVehicle) {
    return section;
  }
  // The attitude plugin's tilt limit, as it will resolve it: configured, else its default.
  const mjfPlugin& plugin = *attitude.descriptor;
  bool has_tilt = false;
  std::string tilt_text;
  for (int k = 0; k < plugin.n_attributes; ++k) {
    if (std::string(plugin.attributes[k].key) != contract::kTiltMax) continue;
    has_tilt = true;
    auto it = config_.attitude.attributes.find(contract::kTiltMax);
    tilt_text = it != config_.attitude.attributes.end() ? it->second.text
                                                        : plugin.attributes[k].default_value;
  }
  const SourceLocation where{config_.source_path, limit->second.line,
                             SectionKey("formation", contract::kAccelLimit)};
  char* end = nullptr;
  const double tilt = has_tilt ? std::strtod(tilt_text.c_str(), &end) : 0.0;
  if (has_tilt && (end == tilt_text.c_str() || !(tilt > 0.0 && tilt < M_PI / 2))) {
    where.Fail("\"vehicle\" needs the attitude plugin's tilt_max in (0, pi/2) (got '" + tilt_text +
               "')");
  }
  double bound = INFINITY;
  for (int i = 1; i < n_vehicles(); ++i) {
    std::string why;
    const double b = VehicleAccelBound(*vehicles_.info[i], has_tilt, tilt, &why);
    if (b < 0.0) {
      where.Fail("\"vehicle\": follower " + std::to_string(i) +
                 " gives no acceleration bound: " + why);
    }
    bound = std::min(bound, b);
  }
  limit->second.text = fmt::format("{:.17g}", bound);
  return section;
}

// A formation law needs a spanning tree and a consistent desired formation.
void ControlWiring::RequireFormationInputs() const {
  try {
    graph_->RequireSpanningTree();
  } catch (const std::invalid_argument& e) {
    SourceLocation{config_.source_path, 0, SectionKey("topology")}.Fail(e.what());
  }
  if (!shape_) {
    throw ConfigError(Where(config_, config_.formation) + " plugin '" + config_.formation.plugin +
                      "' needs a desired formation: add a [formation.shape] table");
  }
  try {
    // Algorithms 1 and 2, step "f_ip' = f_iv": the shape must be self-consistent.
    formation::CheckShapeConsistency(*shape_, 0.0, config_.duration, 0.01, config_.shape.tolerance);
  } catch (const std::invalid_argument& e) {
    SourceLocation{config_.source_path, 0, SectionKey("formation.shape")}.Fail(e.what());
  }
}

// One instance per follower, each created with its own row of L_H only (plus the shape, which
// is mission data every vehicle carries).
std::vector<std::unique_ptr<PluginInstance>> ControlWiring::CreateAgents(
    const LoadedPlugin& agent, const mjfCreateContext& base, const AgentChannel& channel) const {
  RequireFormationInputs();
  std::vector<std::unique_ptr<PluginInstance>> agents;
  for (int i = 0; i < n_followers(); ++i) {
    mjfCreateContext ctx = base;
    ctx.vehicle = i + 1;
    ctx.shape = &abi_shape_;
    ctx.neighbourhood = &channel.neighbourhood(i);
    ctx.model = nullptr;  // a per-agent instance sees no swarm-wide data
    agents.push_back(
        std::make_unique<PluginInstance>(agent, config_.formation, config_.source_path, ctx));
  }
  return agents;
}

std::vector<mjfSetpoint> ControlWiring::InitialSetpoints() const {
  std::vector<mjfSetpoint> setpoints(n_vehicles());
  for (int i = 0; i < n_vehicles(); ++i) {
    mjfSetpoint& s = setpoints[i];
    s = mjfSetpoint{};
    s.sliding[0] = s.sliding[1] = kNaN;
    s.pos[0] = vehicles_.initial_positions[i][0];
    s.pos[1] = vehicles_.initial_positions[i][1];
    s.pos[2] = config_.altitude;
  }
  return setpoints;
}

}  // namespace mjf::runner
