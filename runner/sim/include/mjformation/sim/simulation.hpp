// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One simulation: the scene plan compiled into MuJoCo, the control tick, the actuation model and
// the force stages, stepped as
//   mj_step1 -> true states -> ControlTick (sensors, guidance, formation, attitude)
//   -> Actuation + force stages -> mj_step2.
// Everything a run can get wrong in its input is checked in the constructor, before any step.
#ifndef MJFORMATION_SIM_SIMULATION_HPP_
#define MJFORMATION_SIM_SIMULATION_HPP_

#include <mjformation/plugin.h>
#include <mujoco/mujoco.h>

#include <array>
#include <future>
#include <memory>
#include <mjformation/plugin_contract.hpp>
#include <string>
#include <vector>

#include "mjformation/config/config_error.hpp"
#include "mjformation/config/experiment.hpp"
#include "mjformation/config/state_archive.hpp"
#include "mjformation/control/control_tick.hpp"
#include "mjformation/control/control_wiring.hpp"
#include "mjformation/control/errors.hpp"
#include "mjformation/control/estimated_sensors.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/control/stages.hpp"
#include "mjformation/control/torque_authority.hpp"
#include "mjformation/euler_zyx.hpp"
#include "mjformation/scene/vehicle_binding.hpp"
#include "mjformation/sim/actuation.hpp"
#include "mjformation/sim/partitioned_physics.hpp"

namespace mjf::runner {

class Simulation {
 public:
  // Composes the scene, compiles it, binds sensors and actuators, loads and creates the plugins.
  // Throws ConfigError / SceneError / PluginError with messages naming file, line and key.
  explicit Simulation(const ExperimentConfig& config);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Computes sensors (mj_step1), runs the control tick and hands the controls and external
  // forces to MuJoCo. Throws SimulationError. The same as ComputeSetpoints, ComputeActuation.
  void ComputeControls();
  // The tick in two parts, so that a caller can command the followers in between
  // (CommandFollowers; the Python environments): the true states, the sensors, the leader
  // and the formation stage; then the attitude plugins, actuation and external forces.
  void ComputeSetpoints();
  void ComputeActuation();
  // Between ComputeSetpoints and ComputeActuation: the followers' acceleration commands,
  // [follower][3] (x, y horizontal; z the feedforward on the altitude hold), in place of the
  // formation stage's (ControlTick::CommandFollowers).
  void CommandFollowers(const double* acc) { tick_->CommandFollowers(acc); }
  // In place of ComputeActuation, for followers driven below their attitude plugins: follower
  // i (0-based) with given[i] != 0 gets controls[i * actuators_per_vehicle() ..] as its actuator
  // controls (finite, within range: the caller's job); the leader and every other follower fly
  // their attitude plugins as ComputeActuation flies them.
  void ComputeActuation(const double* controls, const unsigned char* given);
  // Integrates one step (mj_step2) and checks the new state: non-finite values or MuJoCo
  // warnings throw SimulationError.
  void Integrate();

  // Checkpoints and Simulation.get_state (docs/ARCHITECTURE.md, "Checkpoint and resume"):
  // throws ConfigError naming the first stage whose state is not saved yet and the key that
  // switches it on; call before anything runs.
  void RequireSavable() const;
  // Everything the next step depends on, both ways (state_archive.hpp): the step index,
  // MuJoCo's integration state (mj_getState, mjSTATE_INTEGRATION, plugin_state included), the
  // control tick (its setpoint bus, every plugin instance's ABI state and the sensor stage's)
  // and the actuation's and force stages' own state. Between steps only (before ComputeControls);
  // RequireSavable must pass.
  void VisitState(StateArchive& archive);
  // The same taken at a control tick (after ComputeControls or ComputeSetpoints, where the
  // Python Simulation and DrivenSimulation stand): also the tick's outputs (true and measured
  // states, controls); on load MuJoCo's derived quantities are recomputed (mj_step1: positions,
  // velocities, sensors, which read only the restored state) without running a controller
  // again, so that the next ComputeActuation or Integrate continues bit for bit.
  void VisitStateAtTick(StateArchive& archive);

  const ExperimentConfig& config() const { return config_; }
  const mjModel* model() const { return model_.get(); }
  // The whole swarm's state. With partitioned physics ([run] threads > 1) it is brought up to
  // date from the partitions on first access after a step (positions only: what rendering uses).
  mjData* data() {
    SyncWholeData();
    return data_.get();
  }
  const mjData* data() const {
    SyncWholeData();
    return data_.get();
  }
  // Physics partitions stepped in parallel (1: the single whole-swarm model).
  int threads() const { return partitions_ ? partitions_->size() : 1; }
  // The partitions (nullptr with threads = 1).
  PartitionedPhysics* partitions() { return partitions_.get(); }
  // Per-vehicle work between steps that vehicles do not share (recording a row): runs
  // job(context, first, count, error, error_size) over vehicle ranges covering [0, n_vehicles())
  // once, on the partitions' threads (one range each) with partitioned physics, else here.
  // Between ComputeControls and Integrate or after Integrate only (the partitions are idle).
  void ForEachVehicleRange(PartitionedPhysics::RangeJob job, void* context) const;
  const std::string& scene_xml() const { return scene_xml_; }
  // Wall time of composing and compiling the scene (ComposeScene), s.
  double compose_seconds() const { return compose_seconds_; }
  int64_t step_index() const { return step_; }
  int64_t total_steps() const { return total_steps_; }
  double time() const { return static_cast<double>(step_) * config_.timestep; }
  int n_vehicles() const { return static_cast<int>(truth_.size()); }
  int n_followers() const { return n_vehicles() - 1; }
  // The true states (MuJoCo's sensors) of the last ComputeControls.
  const std::vector<mjfVehicleState>& states() const { return truth_; }
  // What the controllers saw (the truth with ideal sensors).
  const std::vector<mjfVehicleState>& measured() const { return tick_->measured(); }
  const std::vector<mjfVehicleState>& measured_states() const { return measured(); }
  // The wind at each vehicle this step (m/s, world); empty when [wind] is calm.
  const std::vector<std::array<double, 3>>& wind() const;
  // The estimator stage ([estimator] plugin other than "passthrough"): each vehicle's
  // estimate and covariance of the last ComputeControls, its plugin instances; else nullptr.
  const EstimatedSensors* estimation() const;
  const std::vector<mjfSetpoint>& setpoints() const { return tick_->setpoints(); }
  const std::vector<double>& controls() const { return tick_->controls(); }
  int actuators_per_vehicle() const { return bindings_.actuators_per_vehicle; }
  const VehicleBinding& binding(int vehicle) const { return bindings_.vehicles[vehicle]; }
  // The desired formation (nullptr when [formation.shape] type = "none").
  const formation::Shape* shape() const { return wiring_->shape(); }
  const PluginInstance& leader_plugin() const { return *tick_->plugins().leader; }
  const PluginInstance* formation_plugin() const { return tick_->formation_law(); }
  // Per-agent execution: the channel stage (network, links, metrics); nullptr in central mode.
  const AgentChannel* channel() const { return tick_->channel(); }
  const PluginInstance& attitude_plugin(int vehicle) const {
    return *tick_->plugins().attitude[vehicle];
  }
  const PluginRegistry& registry() const { return *registry_; }
  // What the runner reads of its plugins (include/mjformation/plugin_contract.hpp), read once
  // after they were created: the only place that looks a contract key up.
  struct PluginContracts {
    plugin::contract::Law law;          // the formation law (input bounds: central mode only)
    plugin::contract::Guidance leader;  // the leader's guidance plugin
    plugin::contract::Attitude attitude;
  };
  const PluginContracts& contracts() const { return contracts_; }
  // The formation plugin's scalar report ("delta", "error_bound", ...), if any.
  std::vector<std::pair<std::string, double>> FormationReport() const;
  // The attitude plugin's report() (e.g. geometric's resolved bandwidths): each key's largest
  // value over the vehicles; empty when the plugin reports nothing.
  std::vector<std::pair<std::string, double>> AttitudeReport() const;
  // Bring your own quadrotor: what adapting the model dropped, renamed and added; for a model
  // that follows the vehicle contract, what composition replaced or kept of its <option> (empty
  // when it sets nothing that differs from the experiment and MuJoCo's defaults).
  const std::vector<std::string>& vehicle_notes() const { return vehicle_notes_; }
  // The follower's torque authority at hover per body axis (runner/control torque_authority.hpp)
  // and its one-line text, for `check`.
  const TorqueAuthority& torque_authority() const { return authority_; }
  // What the attitude plugin reported of its loop (zeros when it reports nothing).
  const AttitudeDemand& attitude_demand() const { return demand_; }
  // What the torque-authority check found wrong (empty: nothing): the attitude loop, as its
  // plugin reports it (att_bw, att_bw_unlimited, tilt_max), asks for more angular acceleration
  // than the vehicle has. Warnings, not refusals (docs/VEHICLES.md).
  // Also: a contract-form model whose site 'imu' is off the centre of mass (by more than
  // kImuOffsetTolerance, m), with the position that fixes it.
  const std::vector<std::string>& warnings() const { return warnings_; }
  static constexpr double kImuOffsetTolerance = 1e-6;

 private:
  void AdaptForeignVehicle(const mjfPlugin& attitude);
  void ReadContracts();
  void CheckTorqueAuthority();
  void NoteUndrivenActuators();
  void CheckImuSite();
  void ComputeForces();
  void HandOverControls();
  void ApplyForces();
  // The partitions' physics from `models` (ComposePartitions of `request`, started when the
  // scene was composed); refuses a model that cannot be partitioned ([run] threads).
  void MakePartitions(const mjfPlugin& attitude, const SceneRequest& request,
                      std::future<PartitionModels>* models);
  void CheckState() const;
  void SyncWholeData() const;

  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };

  ExperimentConfig config_;
  std::unique_ptr<PluginRegistry> registry_;  // outlives every plugin instance
  std::string scene_xml_;
  double compose_seconds_ = 0;
  std::string vehicle_xml_;  // adapted foreign model ([vehicles] body/rotors), else empty
  std::vector<std::string> vehicle_notes_;
  TorqueAuthority authority_;
  AttitudeDemand demand_;
  PluginContracts contracts_;
  std::vector<std::string> warnings_;
  // Freed in reverse order: the tick (plugins may hold pointers into the model) goes first.
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  int64_t step_ = 0;
  int64_t total_steps_ = 0;

  VehicleBindings bindings_;
  std::vector<mjfVehicleState> truth_;

  // The plugins' graph, shape and contexts: declared before the tick, so it outlives the plugins.
  std::unique_ptr<ControlWiring> wiring_;

  std::unique_ptr<ControlTick> tick_;
  std::unique_ptr<Actuation> actuation_;
  std::vector<std::unique_ptr<ForceStage>> force_stages_;
  std::vector<double> external_force_;  // [vehicle][3], N, world frame

  // [run] threads > 1: the physics of the swarm split into partitions; model_ and data_ then
  // hold the whole scene for rendering and the plugins' model pointer, and are not stepped.
  std::unique_ptr<PartitionedPhysics> partitions_;
  mutable bool whole_data_stale_ = false;
};

// EulerZYX (roll, pitch, yaw of a w-x-y-z quaternion) is mjf::EulerZYX, euler_zyx.hpp.
using ::mjf::EulerZYX;

}  // namespace mjf::runner

#endif  // MJFORMATION_SIM_SIMULATION_HPP_
