// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "mjformation/config/paths.hpp"
#include "mjformation/config/source_location.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/vehicle_accel_limit.hpp"
#include "mjformation/core/graph.hpp"
#include "mjformation/core/shape.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/scene/vehicle_adapter.hpp"
#include "mjformation/sim/mujoco_errors.hpp"
#include "mjformation/sim/step_checks.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Where(const ExperimentConfig& c, const PluginSection& s) {
  return SourceLocation{c.source_path, s.line, SectionKey(s.section)}.Prefix();
}

// The plugin named in section `s`, which must be of one of the given kinds.
const LoadedPlugin& FindPlugin(const PluginRegistry& registry, const ExperimentConfig& c,
                               const PluginSection& s, std::initializer_list<mjfKind> kinds,
                               const char* need) {
  const LoadedPlugin& p = registry.Find(s.plugin, Where(c, s) + " plugin");
  for (mjfKind k : kinds) {
    if (p.descriptor->kind == k) return p;
  }
  throw PluginError(Where(c, s) + " plugin: '" + s.plugin + "' is a " +
                    KindName(p.descriptor->kind) + " plugin; " + need);
}

SceneRequest MakeSceneRequest(const ExperimentConfig& c,
                              const std::vector<std::array<double, 3>>& positions,
                              const std::string& vehicle_xml,
                              const std::vector<std::string>& vehicle_notes) {
  SceneRequest request;
  request.scene_path = c.scene_path;
  request.vehicle_path = c.model_path;
  request.positions = positions;
  request.timestep = c.timestep;
  request.offscreen_width = std::max(c.render.width, c.render.video_width);
  request.offscreen_height = std::max(c.render.height, c.render.video_height);
  request.strip_actuators = c.rotor_model == RotorModel::kWrench;
  request.disable_contacts = !c.contacts;
  request.vehicle_xml = vehicle_xml;
  request.vehicle_notes = vehicle_notes;
  return request;
}

}  // namespace

std::array<double, 3> EulerZYX(const double q[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double roll = std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  const double pitch = std::asin(std::clamp(2 * (w * y - z * x), -1.0, 1.0));
  const double yaw = std::atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  return {roll, pitch, yaw};
}

Simulation::Simulation(const ExperimentConfig& config) : config_(config) {
  InstallMujocoHandlers();
  registry_ = std::make_unique<PluginRegistry>(PluginSearchPath(config_.plugin_path));
  const LoadedPlugin& attitude =
      FindPlugin(*registry_, config_, config_.attitude, {MJF_KIND_ATTITUDE},
                 "this section needs an attitude plugin");
  // Attribute problems are reported before the (slower) scene compilation.
  ResolveAttributes(*attitude.descriptor, config_.attitude, config_.source_path);

  initial_positions_ = InitialPositions(config_);
  AdaptForeignVehicle(*attitude.descriptor);  // [vehicles] body / rotors (docs/VEHICLES.md)
  scene_xml_ =
      ComposeScene(MakeSceneRequest(config_, initial_positions_, vehicle_xml_, vehicle_notes_));
  model_.reset(CompileModel(scene_xml_, "composed scene of " + config_.model_path));
  data_.reset(mj_makeData(model_.get()));
  total_steps_ = std::llround(config_.duration / config_.timestep);

  bindings_ = BindVehicles(model_.get(), config_, *attitude.descriptor, vehicle_xml_);
  truth_.resize(config_.followers + 1);
  BuildGraphAndShape();
  std::unique_ptr<AgentChannel> channel = MakeChannel();  // per-agent execution only
  ControlPlugins plugins = CreatePlugins(attitude, channel.get());
  tick_ = std::make_unique<ControlTick>(std::move(plugins), MakeSensorStage(config_),
                                        InitialSetpoints(), bindings_.actuators_per_vehicle,
                                        config_.altitude, config_.timestep, std::move(channel));
  actuation_ = MakeActuation(config_.rotor_model, model_.get(), bindings_, config_.timestep);
  force_stages_ = MakeForceStages(config_);
  external_force_.assign(3 * truth_.size(), 0.0);
  MakePartitions(*attitude.descriptor);
}

// [run] threads > 1: the same scene request, split by vehicle ranges (partitioned_physics.hpp).
void Simulation::MakePartitions(const mjfPlugin& attitude) {
  std::vector<int> bodies;
  for (const VehicleBinding& b : bindings_.vehicles) bodies.push_back(b.body);
  CheckPartitionable(config_, model_.get(), bodies);
  if (config_.threads == 1) return;
  partitions_ = std::make_unique<PartitionedPhysics>(
      config_, MakeSceneRequest(config_, initial_positions_, vehicle_xml_, vehicle_notes_),
      attitude, vehicle_xml_, model_.get());
}

Simulation::~Simulation() = default;

void Simulation::AdaptForeignVehicle(const mjfPlugin& attitude) {
  if (config_.vehicle_body.empty() && config_.vehicle_rotors.empty()) return;
  VehicleMapping m;
  m.model_path = config_.model_path;
  m.body = config_.vehicle_body.empty() ? "vehicle" : config_.vehicle_body;
  for (int k = 0; k < attitude.n_actuators; ++k) m.actuator_names.push_back(attitude.actuators[k]);
  m.rotors = config_.vehicle_rotors.empty() ? m.actuator_names : config_.vehicle_rotors;
  auto where = [&](int line, const char* key) {
    return SourceLocation{config_.source_path, line, SectionKey("vehicles", key)}.Prefix();
  };
  m.body_where = where(config_.vehicle_body_line, "body");
  m.rotors_where = where(config_.vehicle_rotors_line, "rotors");
  AdaptedVehicle adapted = AdaptVehicle(m);
  vehicle_xml_ = std::move(adapted.xml);
  vehicle_notes_ = std::move(adapted.notes);
}

// Graph and shape: checked here so a bad topology fails before any step.
void Simulation::BuildGraphAndShape() {
  for (const auto& e : config_.edges) {
    edge_from_.push_back(e.from);
    edge_to_.push_back(e.to);
    edge_weight_.push_back(e.weight);
  }
  try {
    std::vector<core::Edge> edges;
    for (const auto& e : config_.edges) edges.push_back({e.from, e.to, e.weight});
    graph_ = std::make_unique<core::Graph>(config_.followers, config_.leader_weight, edges);
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
  if (shape_) abi_shape_ = core::ToAbi(*shape_);
}

mjfCreateContext Simulation::VehicleContext(const mjfCreateContext& base, int vehicle) const {
  mjfCreateContext ctx = base;
  ctx.vehicle = vehicle;
  ctx.vehicle_info = &bindings_.vehicles[vehicle].info;
  ctx.initial_pos = initial_positions_[vehicle].data();
  return ctx;
}

// Per-agent execution ([execution] mode = "per_agent"): the channel stage over the simulated
// network. Jacobi exchange is refused (or warned about) where it diverges.
std::unique_ptr<AgentChannel> Simulation::MakeChannel() const {
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
const LoadedPlugin& Simulation::FindAgentPlugin(const LoadedPlugin& named) const {
  if (named.descriptor->kind == MJF_KIND_FORMATION_AGENT) return named;
  const std::string agent_name = config_.formation.plugin + "_agent";
  for (const LoadedPlugin& p : registry_->plugins()) {
    if (p.descriptor->name == agent_name && p.descriptor->kind == MJF_KIND_FORMATION_AGENT) {
      return p;
    }
  }
  throw PluginError(Where(config_, config_.formation) + " plugin: '" + config_.formation.plugin +
                    "' has no per-agent version ('" + agent_name +
                    "') for [execution] mode = \"per_agent\"");
}

ControlPlugins Simulation::CreatePlugins(const LoadedPlugin& attitude,
                                         const AgentChannel* channel) const {
  mjfCreateContext base{};
  base.timestep = config_.timestep;
  base.n_vehicles = n_vehicles();
  base.model = reinterpret_cast<const struct mjModel_*>(model_.get());
  ControlPlugins plugins;
  const LoadedPlugin& leader =
      FindPlugin(*registry_, config_, config_.leader, {MJF_KIND_GUIDANCE},
                 "the leader needs a guidance plugin (e.g. circle, hover)");
  plugins.leader = std::make_unique<PluginInstance>(leader, config_.leader, config_.source_path,
                                                    VehicleContext(base, 0));
  const LoadedPlugin& formation =
      FindPlugin(*registry_, config_, config_.formation,
                 {MJF_KIND_FORMATION, MJF_KIND_GUIDANCE, MJF_KIND_FORMATION_AGENT},
                 "followers need a formation, per-agent formation or guidance plugin");
  if (channel) {
    plugins.formation_agents = CreateAgents(FindAgentPlugin(formation), base, *channel);
  } else if (formation.descriptor->kind == MJF_KIND_FORMATION_AGENT) {
    throw ConfigError(Where(config_, config_.formation) + " plugin: '" + config_.formation.plugin +
                      "' runs one instance per follower: it needs [execution] mode = "
                      "\"per_agent\"");
  } else if (formation.descriptor->kind == MJF_KIND_FORMATION) {
    plugins.formation = CreateFormation(formation, base, FormationSection(attitude));
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

std::unique_ptr<PluginInstance> Simulation::CreateFormation(const LoadedPlugin& formation,
                                                            const mjfCreateContext& base,
                                                            const PluginSection& section) const {
  RequireFormationInputs();
  mjfCreateContext ctx = base;
  ctx.vehicle = -1;
  ctx.graph = &abi_graph_;
  ctx.shape = &abi_shape_;
  return std::make_unique<PluginInstance>(formation, section, config_.source_path, ctx);
}

PluginSection Simulation::FormationSection(const LoadedPlugin& attitude) const {
  PluginSection section = config_.formation;
  auto limit = section.attributes.find("accel_limit");
  if (limit == section.attributes.end() || limit->second.text != "vehicle") return section;
  // The attitude plugin's tilt limit, as it will resolve it: configured, else its default.
  const mjfPlugin& plugin = *attitude.descriptor;
  bool has_tilt = false;
  std::string tilt_text;
  for (int k = 0; k < plugin.n_attributes; ++k) {
    if (std::string(plugin.attributes[k].key) != "tilt_max") continue;
    has_tilt = true;
    auto it = config_.attitude.attributes.find("tilt_max");
    tilt_text = it != config_.attitude.attributes.end() ? it->second.text
                                                        : plugin.attributes[k].default_value;
  }
  const SourceLocation where{config_.source_path, limit->second.line,
                             SectionKey("formation", "accel_limit")};
  char* end = nullptr;
  const double tilt = has_tilt ? std::strtod(tilt_text.c_str(), &end) : 0.0;
  if (has_tilt && (end == tilt_text.c_str() || !(tilt > 0.0 && tilt < M_PI / 2))) {
    where.Fail("\"vehicle\" needs the attitude plugin's tilt_max in (0, pi/2) (got '" + tilt_text +
               "')");
  }
  double bound = INFINITY;
  for (int i = 1; i < n_vehicles(); ++i) {
    std::string why;
    const double b = VehicleAccelBound(bindings_.vehicles[i].info, has_tilt, tilt, &why);
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
void Simulation::RequireFormationInputs() const {
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
    core::CheckShapeConsistency(*shape_, 0.0, config_.duration, 0.01, config_.shape.tolerance);
  } catch (const std::invalid_argument& e) {
    SourceLocation{config_.source_path, 0, SectionKey("formation.shape")}.Fail(e.what());
  }
}

// One instance per follower, each created with its own row of L_H only (plus the shape, which
// is mission data every vehicle carries).
std::vector<std::unique_ptr<PluginInstance>> Simulation::CreateAgents(
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

// Before the first tick every vehicle holds its initial position at the altitude.
std::vector<mjfSetpoint> Simulation::InitialSetpoints() const {
  std::vector<mjfSetpoint> setpoints(n_vehicles());
  for (int i = 0; i < n_vehicles(); ++i) {
    mjfSetpoint& s = setpoints[i];
    s = mjfSetpoint{};
    s.sliding[0] = s.sliding[1] = kNaN;
    s.pos[0] = initial_positions_[i][0];
    s.pos[1] = initial_positions_[i][1];
    s.pos[2] = config_.altitude;
  }
  return setpoints;
}

void Simulation::ComputeControls() {
  ClearMujocoWarning();
  if (partitions_) {
    // The partitions' controls and forces are handed over in Integrate, on their threads; the
    // plugins get no mjData (no single one holds the swarm's state).
    partitions_->Step1(&truth_);
    whole_data_stale_ = true;
    tick_->RunSwarmStages(step_, truth_, reinterpret_cast<const struct mjModel_*>(model_.get()),
                          nullptr);
    // Each vehicle's attitude plugin on its partition's thread (they share nothing).
    partitions_->ForEachRange(
        [](void* tick, int first, int count, char* error, size_t size) {
          static_cast<ControlTick*>(tick)->RunAttitude(first, count, error, size);
        },
        tick_.get());
    if (!force_stages_.empty()) ComputeForces();
    return;
  }
  mj_step1(model_.get(), data_.get());
  ReadTrueStates(data_.get(), bindings_, &truth_);
  tick_->Run(step_, truth_, reinterpret_cast<const struct mjModel_*>(model_.get()),
             reinterpret_cast<const struct mjData_*>(data_.get()));
  if (actuation_->UsesAppliedForces() || !force_stages_.empty()) {
    mju_zero(data_->qfrc_applied, model_->nv);
  }
  actuation_->Apply(tick_->controls(), data_.get());
  if (!force_stages_.empty()) ApplyForces();
}

// Every force stage's force on each vehicle, at its centre of mass.
void Simulation::ComputeForces() {
  std::fill(external_force_.begin(), external_force_.end(), 0.0);
  for (auto& stage : force_stages_) stage->AddForces(step_, time(), truth_, &external_force_);
}

void Simulation::ApplyForces() {
  ComputeForces();
  for (int i = 0; i < n_vehicles(); ++i) {
    const mjtNum wrench[6] = {
        external_force_[3 * i], external_force_[3 * i + 1], external_force_[3 * i + 2], 0, 0, 0};
    AddWrenchAtCentreOfMass(model_.get(), data_.get(), bindings_.vehicles[i].body, wrench);
  }
}

void Simulation::Integrate() {
  if (partitions_) {
    // The simulated time reached on a failure is the one-model run's: the step counts when
    // the failure was the state check after it (see below), not an engine error inside it.
    try {
      partitions_->Step2(tick_->controls(), force_stages_.empty() ? nullptr : &external_force_,
                         static_cast<double>(step_ + 1) * config_.timestep);
    } catch (...) {
      if (partitions_->failed_after_integration()) ++step_;
      throw;
    }
    ++step_;
    return;
  }
  mj_step2(model_.get(), data_.get());
  actuation_->Advance(tick_->controls());
  ++step_;
  CheckState();
}

void Simulation::CheckState() const { CheckStepState(model_.get(), data_.get(), time()); }

void Simulation::SyncWholeData() const {
  if (!whole_data_stale_) return;
  partitions_->CopyInto(model_.get(), data_.get());
  whole_data_stale_ = false;
}

const std::vector<std::array<double, 3>>& Simulation::wind() const {
  static const std::vector<std::array<double, 3>> kCalm;
  for (const auto& stage : force_stages_) {
    if (const auto* w = dynamic_cast<const WindStage*>(stage.get())) return w->wind();
  }
  return kCalm;
}

std::vector<std::pair<std::string, double>> Simulation::FormationReport() const {
  const PluginInstance* formation = formation_plugin();
  if (formation) return formation->Report();
  // Per-agent execution: each key's largest value over the followers (e.g. Theorem 2's delta).
  std::vector<std::pair<std::string, double>> merged;
  for (const auto& agent : tick_->plugins().formation_agents) {
    for (const auto& [key, value] : agent->Report()) {
      auto it = std::find_if(merged.begin(), merged.end(),
                             [&](const auto& kv) { return kv.first == key; });
      if (it == merged.end()) {
        merged.emplace_back(key, value);
      } else {
        it->second = std::max(it->second, value);
      }
    }
  }
  return merged;
}

}  // namespace mjf::runner
