// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/control_tick.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mjformation/control/agent_channel.hpp"
#include "mjformation/control/errors.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string TimeTag(double time) { return fmt::format("t = {:.3f} s", time); }

bool IsFinite(const mjfSetpoint& sp) {
  bool finite = std::isfinite(sp.yaw);
  for (int k = 0; k < 3; ++k) {
    finite =
        finite && std::isfinite(sp.acc[k]) && std::isfinite(sp.pos[k]) && std::isfinite(sp.vel[k]);
  }
  return finite;
}

}  // namespace

ControlTick::ControlTick(ControlPlugins plugins, std::unique_ptr<SensorStage> sensors,
                         std::vector<mjfSetpoint> initial_setpoints, int actuators_per_vehicle,
                         double altitude, double timestep, std::unique_ptr<AgentChannel> channel)
    : plugins_(std::move(plugins)),
      sensors_(std::move(sensors)),
      channel_(std::move(channel)),
      measured_(initial_setpoints.size()),
      setpoints_(std::move(initial_setpoints)),
      controls_(setpoints_.size() * static_cast<size_t>(actuators_per_vehicle), 0.0),
      actuators_per_vehicle_(actuators_per_vehicle),
      altitude_(altitude),
      timestep_(timestep) {}

ControlTick::~ControlTick() {
  // Attitude and follower plugins first, the leader last: the reverse of creation.
  plugins_.attitude.clear();
  plugins_.follower_guidance.clear();
  plugins_.formation_agents.clear();
  plugins_.formation_switches.clear();
  plugins_.formation.reset();
  plugins_.leader.reset();
}

void ControlTick::Run(int64_t step, const std::vector<mjfVehicleState>& truth,
                      const struct mjModel_* model, const struct mjData_* data) {
  RunSwarmStages(step, truth, model, data);
  RunAttitude();
}

void ControlTick::RunSwarmStages(int64_t step, const std::vector<mjfVehicleState>& truth,
                                 const struct mjModel_* model, const struct mjData_* data) {
  const double time = static_cast<double>(step) * timestep_;
  sensors_->Measure(step, time, truth, &measured_);
  SetTickContext(step, model, data);
  RunGuidanceAndFormation(tick_ctx_, truth);
  RequireFiniteSetpoints(time);
}

void ControlTick::SetTickContext(int64_t step, const struct mjModel_* model,
                                 const struct mjData_* data) {
  mjfStepContext& ctx = tick_ctx_;
  ctx = mjfStepContext{};
  ctx.time = static_cast<double>(step) * timestep_;
  ctx.step = step;
  ctx.timestep = timestep_;
  ctx.n_vehicles = n_vehicles();
  ctx.states = measured_.data();
  ctx.setpoints = setpoints_.data();
  ctx.model = model;
  ctx.data = data;
  ctx.error = plugin_error_.data();
  ctx.error_size = plugin_error_.size();
}

void ControlTick::RestoreOutputs(int64_t step, const std::vector<mjfVehicleState>& measured,
                                 const std::vector<double>& controls, const struct mjModel_* model,
                                 const struct mjData_* data) {
  if (measured.size() != measured_.size() || controls.size() != controls_.size()) {
    throw SimulationError("a saved tick of " + std::to_string(measured.size()) +
                          " vehicles cannot be restored into one of " +
                          std::to_string(measured_.size()));
  }
  measured_ = measured;
  controls_ = controls;
  SetTickContext(step, model, data);
}

void ControlTick::RunGuidanceAndFormation(mjfStepContext& ctx,
                                          const std::vector<mjfVehicleState>& truth) {
  Call(*plugins_.leader, ctx, 0);
  ResetFollowerSetpoints();
  SwitchTopology(ctx.step);
  if (PluginInstance* formation = formation_law()) {
    Call(*formation, ctx, -1);
    return;
  }
  if (!plugins_.formation_agents.empty()) {
    RunAgents(ctx, truth);
    return;
  }
  for (size_t i = 0; i < plugins_.follower_guidance.size(); ++i) {
    Call(*plugins_.follower_guidance[i], ctx, static_cast<int>(i) + 1);
  }
}

// The new instance was created with the new graph (the ABI's graph of an instance never
// changes, docs/PLUGINS.md); what the law carries from tick to tick (integrators, adaptive
// gains, its sampling clock) is its declared state, copied over so that only the graph changes.
// A law that declares no state (or another size) starts afresh. The instances taken over stay
// (the state's layout holds every instance, whichever flies).
void ControlTick::SwitchTopology(int64_t step) {
  auto& switches = plugins_.formation_switches;
  while (next_switch_ < switches.size() && switches[next_switch_].step <= step) {
    PluginInstance& old = *formation_law();
    PluginInstance& next = *switches[next_switch_].instance;
    if (old.declares_state() && next.declares_state() && old.state_size() == next.state_size() &&
        old.state_size() > 0) {
      std::vector<double> state(old.state_size());
      old.GetState(state.data());
      next.SetState(state.data());
    }
    ++next_switch_;
  }
}

PluginInstance* ControlTick::formation_law() const {
  return next_switch_ == 0 ? plugins_.formation.get()
                           : plugins_.formation_switches[next_switch_ - 1].instance.get();
}

// Per-agent execution: the channel delivers, then each follower's instance runs each round with
// its own state, its received messages and its own setpoint only (plugin.h, mjfAgentInput).
void ControlTick::RunAgents(const mjfStepContext& ctx, const std::vector<mjfVehicleState>& truth) {
  channel_->BeginTick(ctx.step, ctx.time, truth, measured_, setpoints_);
  mjfStepContext agent_ctx = ctx;
  agent_ctx.states = nullptr;
  agent_ctx.model = nullptr;
  agent_ctx.data = nullptr;
  const AgentClocks& clocks = channel_->clocks();
  if (channel_->rounds_over_links()) {
    RunAgentsOverLinks(agent_ctx, ctx);
    return;
  }
  for (int round = 0; round < channel_->n_rounds(); ++round) {
    for (size_t i = 0; i < plugins_.formation_agents.size(); ++i) {
      if (clocks.active()) {
        // Each follower runs on its own clock ([execution] clock_offset): it samples when that
        // clock says so.
        agent_ctx.time = clocks.Reading(static_cast<int>(i) + 1, ctx.time);
        agent_ctx.step = clocks.LocalStep(static_cast<int>(i), ctx.time);
      }
      agent_ctx.setpoints = &setpoints_[i + 1];
      agent_ctx.agent = &channel_->Input(static_cast<int>(i), round);
      Call(*plugins_.formation_agents[i], agent_ctx, static_cast<int>(i) + 1);
    }
    channel_->EndRound(round, setpoints_);
  }
}

// Exchange rounds over the links (docs/NETWORK.md): the rounds of earlier samples whose inputs
// arrived run first, each with its sample's frozen input, time and step; then every follower's
// round 0 at this tick (which may take a new sample and drop the rounds still missing), then
// the rounds whose inputs arrived in this very step (all of them with latency 0). The last call
// of the tick is round 0 at this tick's time, so the slot diagnostics are this tick's.
void ControlTick::RunAgentsOverLinks(mjfStepContext& agent_ctx, const mjfStepContext& ctx) {
  const AgentClocks& clocks = channel_->clocks();
  auto continue_rounds = [&] {
    int round = 0;
    double local_time = 0.0;
    int64_t local_step = 0;
    for (int i; (i = channel_->NextContinuedRound(&round, &local_time, &local_step)) >= 0;) {
      agent_ctx.time = local_time;
      agent_ctx.step = local_step;
      agent_ctx.setpoints = &setpoints_[i + 1];
      agent_ctx.agent = &channel_->ContinuedInput(i, round);
      Call(*plugins_.formation_agents[i], agent_ctx, i + 1);
      channel_->EndContinuedRound(i, round, setpoints_);
    }
  };
  continue_rounds();
  for (size_t i = 0; i < plugins_.formation_agents.size(); ++i) {
    const int follower = static_cast<int>(i);
    agent_ctx.time = clocks.active() ? clocks.Reading(follower + 1, ctx.time) : ctx.time;
    agent_ctx.step = clocks.active() ? clocks.LocalStep(follower, ctx.time) : ctx.step;
    agent_ctx.setpoints = &setpoints_[i + 1];
    channel_->SetCallContext(follower, agent_ctx.time, agent_ctx.step);
    agent_ctx.agent = &channel_->Input(follower, 0);
    Call(*plugins_.formation_agents[i], agent_ctx, follower + 1);
  }
  channel_->EndSampleRound(setpoints_);
  continue_rounds();
  channel_->HoldPendingCommands(&setpoints_);
}

// The host's part of the bus contract (plugin.h): followers hold the altitude, level, yaw 0;
// formation plugins write only x and y.
void ControlTick::ResetFollowerSetpoints() {
  for (int i = 1; i < n_vehicles(); ++i) {
    mjfSetpoint& sp = setpoints_[i];
    sp.pos[2] = altitude_;
    sp.vel[2] = 0;
    sp.acc[2] = 0;
    sp.yaw = 0;
    sp.sliding[0] = sp.sliding[1] = kNaN;
  }
}

// A non-finite setpoint is named here, with the plugin that wrote it, rather than surfacing
// later as a failure of the attitude plugin that read it.
void ControlTick::RequireFiniteSetpoints(double time) const {
  for (int i = 0; i < n_vehicles(); ++i) {
    if (IsFinite(setpoints_[i])) continue;
    const PluginInstance& writer = i == 0            ? *plugins_.leader
                                   : formation_law() ? *formation_law()
                                   : !plugins_.formation_agents.empty()
                                       ? *plugins_.formation_agents[i - 1]
                                       : *plugins_.follower_guidance[i - 1];
    throw SimulationError(TimeTag(time) + ": plugin '" + writer.descriptor().name +
                          "' wrote a non-finite setpoint for vehicle " + std::to_string(i));
  }
}

void ControlTick::CommandFollowers(const double* acc) {
  for (int i = 1; i < n_vehicles(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double a = acc[3 * (i - 1) + k];
      if (!std::isfinite(a)) {
        throw SimulationError(TimeTag(tick_ctx_.time) + ": the command of follower " +
                              std::to_string(i) + " is not finite");
      }
      setpoints_[i].acc[k] = a;
    }
  }
}

void ControlTick::SetControls(int vehicle, const double* controls) {
  std::copy(controls, controls + actuators_per_vehicle_,
            controls_.begin() + static_cast<ptrdiff_t>(vehicle) * actuators_per_vehicle_);
}

void ControlTick::RunAttitude(int first, int count, char* error, size_t error_size) {
  mjfStepContext ctx = tick_ctx_;
  ctx.error = error;
  ctx.error_size = error_size;
  for (int i = first; i < first + count; ++i) {
    ctx.controls = controls_.data() + static_cast<size_t>(i) * actuators_per_vehicle_;
    Call(*plugins_.attitude[i], ctx, i);
    for (int k = 0; k < actuators_per_vehicle_; ++k) {
      if (!std::isfinite(ctx.controls[k])) {
        throw SimulationError(TimeTag(ctx.time) + ": attitude plugin '" +
                              plugins_.attitude[i]->descriptor().name +
                              "' gave a non-finite control for vehicle " + std::to_string(i) +
                              " (its setpoint or state is not finite)");
      }
    }
  }
}

void ControlTick::Call(PluginInstance& plugin, mjfStepContext& ctx, int vehicle) {
  ctx.error[0] = '\0';
  // Built only on failure: a tick allocates nothing.
  auto who = [&] {
    return TimeTag(ctx.time) + ": plugin '" + plugin.descriptor().name + "'" +
           (vehicle >= 0 ? " (vehicle " + std::to_string(vehicle) + ")" : std::string());
  };
  int code = 0;
  try {
    code = plugin.Compute(ctx);
  } catch (const std::exception& e) {
    // A C++ plugin let an exception out of the C ABI: report it, the run ends cleanly.
    throw SimulationError(who() + " threw: " + e.what());
  } catch (...) {
    throw SimulationError(who() + " threw a non-standard exception");
  }
  if (code == 0) return;
  ctx.error[ctx.error_size - 1] = '\0';
  throw SimulationError(who() + " failed (code " + std::to_string(code) +
                        "): " + (ctx.error[0] ? ctx.error : "no reason given"));
}

std::vector<PluginInstance*> ControlTick::Instances() const {
  std::vector<PluginInstance*> all;
  if (plugins_.leader) all.push_back(plugins_.leader.get());
  if (plugins_.formation) all.push_back(plugins_.formation.get());
  for (const FormationSwitch& s : plugins_.formation_switches) all.push_back(s.instance.get());
  for (const auto* group :
       {&plugins_.follower_guidance, &plugins_.formation_agents, &plugins_.attitude}) {
    for (const auto& p : *group) all.push_back(p.get());
  }
  return all;
}

void ControlTick::RequireSavable() const {
  if (channel_) {
    const std::string why = NativeNetworkRefusal(channel_->config(), timestep_);
    if (!why.empty()) throw SimulationError(why);
  }
  if (!sensors_->saves_state()) {
    throw SimulationError(
        "the sensor stage does not declare its state: a tick with it cannot be copied or "
        "checkpointed");
  }
  sensors_->RequireNativeState();
}

// The bus: every mjfSetpoint is doubles only (plugin.h), written as its kSetpointDoubles.
namespace {
constexpr size_t kSetpointDoubles = sizeof(mjfSetpoint) / sizeof(double);
static_assert(sizeof(mjfSetpoint) == 12 * sizeof(double), "mjfSetpoint holds doubles only");
}  // namespace

size_t ControlTick::StateSize() const {
  size_t n = setpoints_.size() * kSetpointDoubles + SwitchesTakenSize();
  for (const PluginInstance* p : Instances()) n += p->state_size();
  if (stage_state_size_ == kUnsized) {
    // Fixed at construction (fixed_state_archive.hpp): counted once.
    FixedStateArchive sizing = FixedStateArchive::Sizing();
    VisitStageState(sizing);
    stage_state_size_ = sizing.size();
  }
  return n + stage_state_size_;
}

// The stages' fixed-length blocks: the sensor stage's, then the channel's (per-agent execution).
void ControlTick::VisitStageState(FixedStateArchive& archive) const {
  sensors_->VisitState(archive);
  if (channel_) channel_->VisitState(archive);
}

void ControlTick::GetState(double* out) const { WriteState(out, false); }
void ControlTick::UpdateState(double* block) const { WriteState(block, true); }

void ControlTick::WriteState(double* out, bool updating) const {
  std::memcpy(out, setpoints_.data(), setpoints_.size() * sizeof(mjfSetpoint));
  out += setpoints_.size() * kSetpointDoubles;
  if (SwitchesTakenSize()) *out++ = static_cast<double>(next_switch_);
  for (const PluginInstance* p : Instances()) {
    p->GetState(out);
    out += p->state_size();
  }
  FixedStateArchive saving =
      updating ? FixedStateArchive::Updating(out) : FixedStateArchive::Saving(out);
  VisitStageState(saving);
}

void ControlTick::SetState(const double* in) {
  std::memcpy(setpoints_.data(), in, setpoints_.size() * sizeof(mjfSetpoint));
  in += setpoints_.size() * kSetpointDoubles;
  if (SwitchesTakenSize()) {
    const double taken = *in++;
    if (!(taken >= 0 && taken <= static_cast<double>(plugins_.formation_switches.size()) &&
          taken == static_cast<double>(static_cast<size_t>(taken)))) {
      throw StateArchiveError("the saved state holds " + std::to_string(taken) +
                              " topology switches taken, where this configuration has " +
                              std::to_string(plugins_.formation_switches.size()));
    }
    next_switch_ = static_cast<size_t>(taken);
  }
  for (PluginInstance* p : Instances()) {
    p->SetState(in);
    in += p->state_size();
  }
  FixedStateArchive loading = FixedStateArchive::Loading(in);
  VisitStageState(loading);
}

}  // namespace mjf::runner
