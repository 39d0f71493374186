// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One control tick on plain arrays, with no MuJoCo in it:
//   true states -> sensor stage -> leader guidance -> formation (or a guidance per follower)
//   -> attitude per vehicle -> controls.
// The simulation hands it the true states and applies the controls it returns; a unit test can
// drive it alone (tests/runner/control/control_tick_test.cc), as PX4's PositionControl is tested
// without its module. Every plugin failure becomes a SimulationError naming plugin, vehicle and
// time.
#ifndef MJFORMATION_CONTROL_CONTROL_TICK_HPP_
#define MJFORMATION_CONTROL_CONTROL_TICK_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/plugin_host.hpp"
#include "mjformation/control/stages.hpp"

namespace mjf::runner {

// The plugin instances of one simulation. Exactly one of `formation`, `formation_agents` and
// `follower_guidance` is used: a formation-kind plugin for the swarm, a per-agent formation
// plugin per follower (over an AgentChannel), or a guidance plugin per follower.
// A formation-law instance created with a later graph ([[topology.switch]]): it replaces
// `formation` on the first tick at or after physics step `step`.
struct FormationSwitch {
  int64_t step = 0;
  std::unique_ptr<PluginInstance> instance;
};

struct ControlPlugins {
  std::unique_ptr<PluginInstance> leader;
  std::unique_ptr<PluginInstance> formation;
  std::vector<FormationSwitch> formation_switches;  // in time order; empty: one graph
  std::vector<std::unique_ptr<PluginInstance>> follower_guidance;  // [followers]
  std::vector<std::unique_ptr<PluginInstance>> formation_agents;   // [followers]
  std::vector<std::unique_ptr<PluginInstance>> attitude;           // [vehicles]
};

class ControlTick {
 public:
  // initial_setpoints: the bus before the first tick (positions held, sliding NaN).
  // channel: the communication stage, required with formation_agents (null otherwise).
  ControlTick(ControlPlugins plugins, std::unique_ptr<SensorStage> sensors,
              std::vector<mjfSetpoint> initial_setpoints, int actuators_per_vehicle,
              double altitude, double timestep, std::unique_ptr<AgentChannel> channel = nullptr);
  ~ControlTick();
  ControlTick(const ControlTick&) = delete;
  ControlTick& operator=(const ControlTick&) = delete;

  // One tick at physics step `step` (time = step * timestep). `model` and `data` are handed to
  // the plugins as raw access and may be NULL. Throws SimulationError.
  void Run(int64_t step, const std::vector<mjfVehicleState>& truth,
           const struct mjModel_* model = nullptr, const struct mjData_* data = nullptr);
  // Run in two parts, for partitioned physics: first everything the swarm shares (sensors,
  // guidance, formation, the setpoint check), then the attitude plugins of vehicles
  // [first, first + count). Each attitude instance reads only its own vehicle's state and
  // setpoint and writes only its own controls, so ranges may run on different threads at once,
  // each with its own `error` buffer (error_size chars) for the plugins' messages.
  void RunSwarmStages(int64_t step, const std::vector<mjfVehicleState>& truth,
                      const struct mjModel_* model, const struct mjData_* data);
  void RunAttitude(int first, int count, char* error, size_t error_size);
  // Every vehicle's attitude plugin, after RunSwarmStages (Run is the two in a row).
  void RunAttitude() { RunAttitude(0, n_vehicles(), plugin_error_.data(), plugin_error_.size()); }
  // Vehicles [first, first + count)'s attitude plugins, on the caller's thread.
  void RunAttitude(int first, int count) {
    RunAttitude(first, count, plugin_error_.data(), plugin_error_.size());
  }
  // In place of vehicle i's attitude plugin: its actuator controls, as given (finite, checked
  // by the caller), after RunSwarmStages.
  void SetControls(int vehicle, const double* controls);
  // Replaces the followers' horizontal commands the formation stage wrote, between
  // RunSwarmStages and RunAttitude: acc[3 * (i - 1) + k] becomes setpoint i's acc[k] (followers
  // i = 1..N; k = 0, 1 the horizontal command, 2 the vertical feedforward on the altitude hold).
  // The formation stage's slots (pos, vel) stay. Throws SimulationError on a non-finite value.
  void CommandFollowers(const double* acc);

  // The tick's state, what one Run leaves for the next: the setpoint bus, then each plugin
  // instance's declared state (leader, formation, follower guidance, per-agent formation,
  // attitude; ABI 4), then the sensor stage's (noise streams, latency buffers, bias and
  // wander, the estimator instances' ABI state and estimates: SensorStage::VisitState), then
  // the channel's in per-agent execution (AgentChannel::VisitState: links' streams, messages in
  // flight and held, ages), of a length fixed at construction. After SetState(GetState()) of
  // another tick built from the same configuration, Run gives the same bits. RequireSavable()
  // throws naming the first stage the native MuJoCo plugin cannot hold (a switching topology, a
  // latency buffer past kNativeLatencySteps, an estimator without declared state, a channel
  // NativeNetworkRefusal refuses).
  void RequireSavable() const;
  size_t StateSize() const;
  void GetState(double* out) const;
  // GetState into a block that holds the state this tick last got or set (plugin_state from one
  // step to the next): the random streams' words are written only after they change
  // (FixedStateArchive::Updating). Same result as GetState, less to write.
  void UpdateState(double* block) const;
  void SetState(const double* in);
  // Beside the fixed block, for checkpoints only: the channel's lists that grow with the run
  // (AgentChannel::VisitEvents); nothing without a channel.
  void VisitGrowingState(StateArchive& archive) {
    if (channel_) channel_->VisitEvents(archive);
  }
  // A tick restored between its two parts (the Python Simulation stands after a tick): what it
  // measured and the controls it computed, and the context the attitude stage runs in, as
  // RunSwarmStages of `step` left them, without running a plugin.
  void RestoreOutputs(int64_t step, const std::vector<mjfVehicleState>& measured,
                      const std::vector<double>& controls, const struct mjModel_* model,
                      const struct mjData_* data);

  int n_vehicles() const { return static_cast<int>(setpoints_.size()); }
  int actuators_per_vehicle() const { return actuators_per_vehicle_; }
  // What the controllers saw on the last tick (the truth with ideal sensors).
  const std::vector<mjfVehicleState>& measured() const { return measured_; }
  const std::vector<mjfSetpoint>& setpoints() const { return setpoints_; }
  const std::vector<double>& controls() const { return controls_; }  // [vehicle][actuator]
  const ControlPlugins& plugins() const { return plugins_; }
  // The central formation law flying now: plugins().formation until the first topology switch,
  // then the instance of the last switch taken (null without a central formation law).
  PluginInstance* formation_law() const;
  const AgentChannel* channel() const { return channel_.get(); }
  // Drops the range topology's events recorded so far (network::Network::ForgetEvents).
  void ForgetTopologyEvents() {
    if (channel_) channel_->ForgetTopologyEvents();
  }
  const SensorStage& sensors() const { return *sensors_; }

 private:
  void RunGuidanceAndFormation(mjfStepContext& ctx, const std::vector<mjfVehicleState>& truth);
  void SetTickContext(int64_t step, const struct mjModel_* model, const struct mjData_* data);
  // Hands the formation law over to the instance of every switch due by `step`.
  void SwitchTopology(int64_t step);
  // The channel stage: each follower's instance, handed only its own state and messages.
  void RunAgents(const mjfStepContext& ctx, const std::vector<mjfVehicleState>& truth);
  void RunAgentsOverLinks(mjfStepContext& agent_ctx, const mjfStepContext& ctx);
  void ResetFollowerSetpoints();
  void RequireFiniteSetpoints(double time) const;
  // Calls the plugin and turns a failure code or a C++ exception into a SimulationError.
  void Call(PluginInstance& plugin, mjfStepContext& ctx, int vehicle);
  // The sensor stage's and the channel's blocks (their state is theirs to change, even when
  // walked by a GetState: the walk writes through the archive, it changes nothing).
  void VisitStageState(FixedStateArchive& archive) const;
  // GetState and UpdateState: the stages' blocks through `updating` or a plain Saving.
  void WriteState(double* out, bool updating) const;
  // Every plugin instance, in the order of the state layout (every switch's instance too).
  std::vector<PluginInstance*> Instances() const;
  // The switches taken (next_switch_) in the state: one double, with [[topology.switch]] only.
  size_t SwitchesTakenSize() const { return plugins_.formation_switches.empty() ? 0 : 1; }

  ControlPlugins plugins_;
  size_t next_switch_ = 0;  // the first of plugins_.formation_switches not yet taken over
  std::unique_ptr<SensorStage> sensors_;
  std::unique_ptr<AgentChannel> channel_;
  std::vector<mjfVehicleState> measured_;
  std::vector<mjfSetpoint> setpoints_;
  std::vector<double> controls_;
  int actuators_per_vehicle_;
  double altitude_;
  double timestep_;
  std::array<char, 512> plugin_error_{};
  mjfStepContext tick_ctx_{};  // the context of the current tick (RunSwarmStages)
  static constexpr size_t kUnsized = static_cast<size_t>(-1);
  mutable size_t stage_state_size_ = kUnsized;  // the sensor stage's and channel's, counted once
};

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_CONTROL_TICK_HPP_
