// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>

#include "mjformation/config/paths.hpp"
#include "mjformation/config/source_location.hpp"
#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/control_setup.hpp"
#include "mjformation/scene/scene.hpp"
#include "mjformation/scene/vehicle_adapter.hpp"
#include "mjformation/sim/mujoco_errors.hpp"
#include "mjformation/sim/step_checks.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::runner {
namespace {

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

Simulation::Simulation(const ExperimentConfig& config) : config_(config) {
  InstallMujocoHandlers();
  registry_ = std::make_unique<PluginRegistry>(PluginSearchPath(config_.plugin_path));
  // Attribute problems are reported before the (slower) scene compilation.
  const LoadedPlugin& attitude = LoadAttitudePlugin(*registry_, config_);

  std::vector<std::array<double, 3>> initial_positions = InitialPositions(config_);
  AdaptForeignVehicle(*attitude.descriptor);  // [vehicles] body / rotors (docs/VEHICLES.md)
  const SceneRequest request =
      MakeSceneRequest(config_, initial_positions, vehicle_xml_, vehicle_notes_);
  // Partitioned physics: the partitions' models are composed on a thread of their own while
  // this one composes the whole swarm's (composing is most of a large swarm's start, the two do
  // not depend on each other; their peak memory adds up, docs/PERFORMANCE.md). More threads than
  // vehicles start nothing here: CheckPartitionable refuses them after the whole swarm's model.
  std::future<PartitionModels> partition_models;
  if (config_.threads > 1 && config_.threads <= static_cast<int>(request.positions.size())) {
    partition_models = std::async(std::launch::async, ComposePartitions, config_.threads, request);
  }
  const auto compose_start = std::chrono::steady_clock::now();
  ComposedScene scene = ComposeScene(request, "composed scene of " + config_.model_path);
  compose_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - compose_start).count();
  scene_xml_ = std::move(scene.xml);
  if (vehicle_xml_.empty()) vehicle_notes_ = std::move(scene.notes);
  model_.reset(scene.model.release());
  data_.reset(mj_makeData(model_.get()));
  total_steps_ = NearestStep(config_.duration, config_.timestep);

  bindings_ = BindVehicles(model_.get(), config_, *attitude.descriptor, vehicle_xml_);
  truth_.resize(config_.followers + 1);
  VehicleContexts contexts;
  for (const VehicleBinding& b : bindings_.vehicles) contexts.info.push_back(&b.info);
  contexts.initial_positions = std::move(initial_positions);  // the wiring owns them from here
  contexts.model = reinterpret_cast<const struct mjModel_*>(model_.get());
  ControlSetup control = SetUpControl(config_, *registry_, attitude, std::move(contexts),
                                      bindings_.actuators_per_vehicle);
  wiring_ = std::move(control.wiring);
  tick_ = std::move(control.tick);
  actuation_ =
      WithRotorFaults(MakeActuation(config_.rotor_model, model_.get(), bindings_, config_.timestep),
                      config_, bindings_, 0);
  force_stages_ = MakeForceStages(config_);
  external_force_.assign(3 * truth_.size(), 0.0);
  MakePartitions(*attitude.descriptor, request, &partition_models);
  ReadContracts();
  CheckTorqueAuthority();
  CheckImuSite();
  NoteUndrivenActuators();
}

// Actuators of the vehicle that no plugin drives are said, not silently left at their ctrl (after
// the scene's composition: the note is the run's, not the composed scene's header).
void Simulation::NoteUndrivenActuators() {
  const std::vector<std::string>& undriven = bindings_.undriven_actuators;
  if (undriven.empty()) return;
  std::string names;
  for (const std::string& name : undriven) names += (names.empty() ? "'" : ", '") + name + "'";
  vehicle_notes_.push_back("actuators not driven by the attitude plugin '" +
                           config_.attitude.plugin +
                           "' (they keep their ctrl, 0 unless set): " + names);
}

// The contract's values: the formation law's report (the largest over the followers in
// per-agent execution) and input bounds, the leader's acceleration bounds, the attitude report.
// The law's bounds are read only of a central formation plugin: with per-agent execution the
// leader's bounds are the ones checked, as they always were.
void Simulation::ReadContracts() {
  for (const auto& [key, value] : FormationReport()) {
    plugin::contract::SetReported(contracts_.law, key.c_str(), value);
  }
  if (const PluginInstance* formation = formation_plugin()) {
    for (const auto& [key, text] : formation->attributes()) {
      plugin::contract::SetAttribute(contracts_.law, key.c_str(), text.c_str());
    }
  }
  for (const auto& [key, text] : leader_plugin().attributes()) {
    plugin::contract::SetAttribute(contracts_.leader, key.c_str(), text.c_str());
  }
  for (const auto& [key, value] : AttitudeReport()) {
    plugin::contract::SetReported(contracts_.attitude, key.c_str(), value);
  }
}

// Every vehicle is a copy of one model, so the first follower's info (the leader's when there
// is none) stands for all. The demand is what the attitude plugin reports of its loop; a plugin
// that reports no att_bw and tilt_max gets the authority listed and nothing judged.
void Simulation::CheckTorqueAuthority() {
  const int vehicle = n_vehicles() > 1 ? 1 : 0;
  authority_ = ComputeTorqueAuthority(bindings_.vehicles[vehicle].info);
  // A value the plugin does not report is 0 to the check: nothing judged.
  const auto or_zero = [](double v) { return std::isnan(v) ? 0.0 : v; };
  const plugin::contract::Attitude& a = contracts_.attitude;
  demand_.att_bw = or_zero(a.att_bw);
  demand_.att_bw_unlimited = or_zero(a.att_bw_unlimited);
  demand_.tilt_max = or_zero(a.tilt_max);
  std::string name = "vehicle model " + config_.model_path;
  if (!config_.vehicle_body.empty()) name += " (body '" + config_.vehicle_body + "')";
  warnings_ = AuthorityWarnings(authority_, demand_, name);
}

// [run] threads > 1: the whole swarm's scene request, split by vehicle ranges
// (partitioned_physics.hpp); `models` was started with it in the constructor.
void Simulation::MakePartitions(const mjfPlugin& attitude, const SceneRequest& request,
                                std::future<PartitionModels>* models) {
  std::vector<int> bodies;
  for (const VehicleBinding& b : bindings_.vehicles) bodies.push_back(b.body);
  CheckPartitionable(config_, model_.get(), bodies);
  if (config_.threads == 1) return;
  partitions_ = std::make_unique<PartitionedPhysics>(config_, request, models->get(), attitude,
                                                     vehicle_xml_, model_.get());
}

Simulation::~Simulation() = default;

// The controllers take what the sensors read at the site 'imu' for the centre of mass's position
// and velocity (the paper's double integrator, eq. (1)); a site off the centre of mass adds the
// lever arm's motion (omega x r) to them, and the formation flies differently. The adapter puts
// its site at the centre of mass; a contract-form model's own site is checked here, on vehicle 0
// (every vehicle is a copy), and a warning says where it is and where it belongs.
void Simulation::CheckImuSite() {
  const VehicleBinding& v = bindings_.vehicles[0];
  const int site = mj_name2id(model_.get(), mjOBJ_SITE, (VehiclePrefix(0) + "imu").c_str());
  if (site < 0) return;
  std::unique_ptr<mjData, DataDeleter> d(mj_makeData(model_.get()));
  mj_kinematics(model_.get(), d.get());
  mj_comPos(model_.get(), d.get());
  const int b = v.body;
  double rel_site[3], rel_com[3], site_body[3], com_body[3];
  mju_sub3(rel_site, d->site_xpos + 3 * site, d->xpos + 3 * b);
  mju_sub3(rel_com, d->subtree_com + 3 * b, d->xpos + 3 * b);
  mju_mulMatTVec(site_body, d->xmat + 9 * b, rel_site, 3, 3);  // world -> body axes: R^T x
  mju_mulMatTVec(com_body, d->xmat + 9 * b, rel_com, 3, 3);
  double offset[3];
  mju_sub3(offset, site_body, com_body);
  const double distance = mju_norm3(offset);
  // MuJoCo compiles a site at NaN; every sensor of it would then read NaN, and the run would
  // stop at t = 0 blaming the vehicle's state instead of the model.
  if (!std::isfinite(distance)) {
    char text[400];
    std::snprintf(text, sizeof(text),
                  "vehicle model %s: the site 'imu' is at %.6g %.6g %.6g in the body's axes, "
                  "not a finite position: give <site name=\"imu\"> a finite pos (at the centre "
                  "of mass, %.6g %.6g %.6g, docs/VEHICLES.md, \"The imu site\")",
                  config_.model_path.c_str(), site_body[0], site_body[1], site_body[2], com_body[0],
                  com_body[1], com_body[2]);
    throw SceneError(text);
  }
  if (distance <= kImuOffsetTolerance) return;
  char text[600];
  std::snprintf(text, sizeof(text),
                "vehicle model %s: the site 'imu' (at %.6g %.6g %.6g in the body's axes) is %.4g m "
                "from the centre of mass (%.6g %.6g %.6g): the sensors pos and vel read the "
                "site, which the controllers take for the centre of mass, so every rotation "
                "shows as a position and velocity error and the formation flies differently; "
                "put <site name=\"imu\"> at pos=\"%.6g %.6g %.6g\" unless the offset is what "
                "you study (docs/VEHICLES.md, \"The imu site\")",
                config_.model_path.c_str(), site_body[0], site_body[1], site_body[2], distance,
                com_body[0], com_body[1], com_body[2], com_body[0], com_body[1], com_body[2]);
  warnings_.push_back(text);
}

void Simulation::AdaptForeignVehicle(const mjfPlugin& attitude) {
  AdaptedVehicle adapted = AdaptConfiguredVehicle(config_, attitude);
  vehicle_xml_ = std::move(adapted.xml);
  vehicle_notes_ = std::move(adapted.notes);
}

void Simulation::ComputeControls() {
  ComputeSetpoints();
  ComputeActuation();
}

void Simulation::ComputeSetpoints() {
  ClearMujocoWarning();
  if (partitions_) {
    // The partitions' controls and forces are handed over in Integrate, on their threads; the
    // plugins get no mjData (no single one holds the swarm's state).
    partitions_->Step1(&truth_);
    whole_data_stale_ = true;
    tick_->RunSwarmStages(step_, truth_, reinterpret_cast<const struct mjModel_*>(model_.get()),
                          nullptr);
    return;
  }
  mj_step1(model_.get(), data_.get());
  ReadTrueStates(data_.get(), bindings_, &truth_);
  tick_->RunSwarmStages(step_, truth_, reinterpret_cast<const struct mjModel_*>(model_.get()),
                        reinterpret_cast<const struct mjData_*>(data_.get()));
}

void Simulation::ComputeActuation() {
  if (partitions_) {
    // Each vehicle's attitude plugin on its partition's thread (they share nothing).
    partitions_->ForEachRange(
        [](void* tick, int first, int count, char* error, size_t size) {
          static_cast<ControlTick*>(tick)->RunAttitude(first, count, error, size);
        },
        tick_.get());
    if (!force_stages_.empty()) ComputeForces();
    return;
  }
  tick_->RunAttitude();
  HandOverControls();
}

void Simulation::ComputeActuation(const double* controls, const unsigned char* given) {
  // On this thread, also with partitions: they take the tick's controls in Integrate.
  tick_->RunAttitude(0, 1);
  const int per = actuators_per_vehicle();
  for (int i = 0; i < n_followers(); ++i) {
    if (given[i]) {
      tick_->SetControls(i + 1, controls + static_cast<ptrdiff_t>(i) * per);
    } else {
      tick_->RunAttitude(i + 1, 1);
    }
  }
  if (partitions_) {
    if (!force_stages_.empty()) ComputeForces();
    return;
  }
  HandOverControls();
}

// The tick's controls and the force stages' forces to the single model's mjData: forces are
// added into the qfrc_passive that mj_step1 computed (AddWrenchAtCentreOfMass).
void Simulation::HandOverControls() {
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

void Simulation::ForEachVehicleRange(PartitionedPhysics::RangeJob job, void* context) const {
  if (partitions_) {
    partitions_->ForEachRange(job, context);  // the pool is idle between phases
    return;
  }
  char error[1] = {'\0'};
  job(context, 0, n_vehicles(), error, sizeof(error));
}

void Simulation::CheckState() const { CheckStepState(model_.get(), data_.get(), time()); }

void Simulation::SyncWholeData() const {
  if (!whole_data_stale_) return;
  partitions_->CopyInto(model_.get(), data_.get());
  whole_data_stale_ = false;
}

const EstimatedSensors* Simulation::estimation() const {
  return dynamic_cast<const EstimatedSensors*>(&tick_->sensors());
}

const std::vector<std::array<double, 3>>& Simulation::wind() const {
  static const std::vector<std::array<double, 3>> kCalm;
  for (const auto& stage : force_stages_) {
    if (const auto* w = dynamic_cast<const WindStage*>(stage.get())) return w->wind();
  }
  return kCalm;
}

namespace {
// Each key's largest value over the instances (e.g. Theorem 2's delta over the followers).
template <typename Instances>
std::vector<std::pair<std::string, double>> LargestOverInstances(const Instances& instances) {
  std::vector<std::pair<std::string, double>> merged;
  for (const auto& instance : instances) {
    for (const auto& entry : instance->Report()) {
      // Not a structured binding: Clang 14 (the fuzz build) cannot capture one in a lambda.
      const std::string& key = entry.first;
      auto it = std::find_if(merged.begin(), merged.end(),
                             [&](const auto& kv) { return kv.first == key; });
      if (it == merged.end()) {
        merged.push_back(entry);
      } else {
        it->second = std::max(it->second, entry.second);
      }
    }
  }
  return merged;
}
}  // namespace

std::vector<std::pair<std::string, double>> Simulation::FormationReport() const {
  const PluginInstance* formation = formation_plugin();
  if (formation) return formation->Report();
  return LargestOverInstances(tick_->plugins().formation_agents);  // per-agent execution
}

std::vector<std::pair<std::string, double>> Simulation::AttitudeReport() const {
  return LargestOverInstances(tick_->plugins().attitude);
}

}  // namespace mjf::runner
