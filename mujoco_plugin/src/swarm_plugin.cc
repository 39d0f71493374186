// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation.swarm: a native MuJoCo engine plugin (mjpPlugin) that flies the vehicles of an
// exported scene with our controllers, through SwarmHost (the bridge to our own plugin ABI).
//
// Timing. MuJoCo calls actuator plugins inside mj_fwdActuation, after every position and
// velocity sensor of the step has been computed: the same sensor values the runner reads
// between mj_step1 and mj_step2. Our plugins are stateful (a formation law samples every T and
// holds; pd_cascade integrates) and their state is opaque, so the tick of physics step k runs
// once, at the first evaluation of step k; its controls are held in plugin_state with the step
// they belong to. Every further evaluation of the same step (mj_forward again and again in a
// paused viewer) reuses them: compute is idempotent. advance() commits the step, so the next
// evaluation runs the next tick.
//
// Actuation. The runner writes its controls into d->ctrl; MuJoCo then clamps them to
// ctrlrange and, for a filter actuator, sets act_dot = (ctrl - act) / max(mjMINVAL, tau), and
// for an actuator without activation, force = gain * ctrl. This plugin writes the same two
// quantities, with the same operations, from its held controls: in actuator_act_dot (called
// after MuJoCo's own act_dot) and in compute (called after MuJoCo's own forces). The
// vehicles' actuators keep their MJCF definitions; d->ctrl of a driven actuator is unused.
#include <mujoco/mjplugin.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "swarm_host.hpp"

namespace mjf::native {
namespace {

constexpr char kName[] = "mjformation.swarm";
// State: [0] the physics step whose controls are held (-1: none), [1] the last committed step,
// [2 + a] the held control of actuator a (NaN: not driven by this instance).
constexpr int kHeader = 2;

std::vector<const char*> AttributeNames() {
  std::vector<const char*> names;
  for (const std::string& s : CarriedSections()) names.push_back(s.c_str());
  return names;
}

std::string InstanceWhere(const mjModel* m, int instance) {
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  return std::string("MJCF plugin '") + kName + "' instance '" +
         (name && name[0] ? name : std::to_string(instance)) + "'";
}

runner::ExperimentConfig ReadConfig(const mjModel* m, int instance) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& key : CarriedSections()) {
    const char* value = mj_getPluginConfig(m, instance, key.c_str());
    pairs.emplace_back(key, value ? value : "");
  }
  return ConfigFromPairs(pairs, InstanceWhere(m, instance));
}

// Builds a host on a thread of its own. The host loads the vehicle model (a compile of its
// own), and MuJoCo keeps the compiler's error jump per thread: a compile nested on the
// compiling thread would leave the outer compile's jump pointing into a finished frame.
std::unique_ptr<SwarmHost> MakeHost(const mjModel* m, int instance) {
  std::unique_ptr<SwarmHost> host;
  std::exception_ptr failure;
  std::thread builder([&] {
    try {
      host = std::make_unique<SwarmHost>(m, ReadConfig(m, instance));
    } catch (...) {
      failure = std::current_exception();
    }
  });
  builder.join();
  if (failure) std::rethrow_exception(failure);
  return host;
}

// Called while the model compiles. The experiment parser checks every section here (names,
// values, messages as for an experiment file); our plugins' create() checks their attributes
// in Init, which the compiler also runs on a trial mjData. Either refusal becomes the compile
// error: mju_error here, mju_warning + -1 there (MuJoCo appends the warning to its error).
int NState(const mjModel* m, int instance) {
  std::string error;
  try {
    ReadConfig(m, instance);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!error.empty()) mju_error("%s", error.c_str());
  return kHeader + m->nu;
}

void ClearState(const mjModel* m, mjtNum* state) {
  state[0] = -1;
  state[1] = -1;
  for (int a = 0; a < m->nu; ++a) state[kHeader + a] = std::numeric_limits<double>::quiet_NaN();
}

SwarmHost* Host(const mjData* d, int instance) {
  return reinterpret_cast<SwarmHost*>(d->plugin_data[instance]);
}

int Init(const mjModel* m, mjData* d, int instance) {
  try {
    std::unique_ptr<SwarmHost> host = MakeHost(m, instance);
    d->plugin_data[instance] = reinterpret_cast<uintptr_t>(host.release());
  } catch (const std::exception& e) {
    mju_warning("%s", e.what());
    return -1;
  }
  ClearState(m, d->plugin_state + m->plugin_stateadr[instance]);
  return 0;
}

void Destroy(mjData* d, int instance) {
  delete Host(d, instance);
  d->plugin_data[instance] = 0;
}

// Our plugins' own state cannot be rewound, so a reset builds the host again from the model.
void Reset(const mjModel* m, mjtNum* plugin_state, void* plugin_data, int instance) {
  ClearState(m, plugin_state);
  if (!plugin_data) return;  // mj_makeData resets before init
  try {
    static_cast<SwarmHost*>(plugin_data)->Restart(m);
  } catch (const std::exception& e) {
    mju_error("%s: %s", InstanceWhere(m, instance).c_str(), e.what());
  }
}

mjtNum* State(const mjModel* m, mjData* d, int instance) {
  return d->plugin_state + m->plugin_stateadr[instance];
}

// The tick of the current step, once (see the file comment).
mjtNum* HeldControls(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  const int64_t step = std::llround(d->time / m->opt.timestep);
  if (state[0] != static_cast<double>(step)) {
    if (state[1] >= 0 && static_cast<double>(step) != state[1] + 1) {
      mju_error(
          "%s: the scene was stepped to t = %g s outside the plugin (step %lld after "
          "step %.0f); reset the data (mj_resetData) to fly again",
          InstanceWhere(m, instance).c_str(), d->time, static_cast<long long>(step), state[1]);
    }
    try {
      Host(d, instance)->Tick(step, m, d, state + kHeader);
    } catch (const std::exception& e) {
      mju_error("%s: %s", InstanceWhere(m, instance).c_str(), e.what());
    }
    state[0] = static_cast<double>(step);
  }
  return state + kHeader;
}

double Clamped(const mjModel* m, int a, double u) {
  if (!m->actuator_ctrllimited[a]) return u;
  return mju_clip(u, m->actuator_ctrlrange[2 * a], m->actuator_ctrlrange[2 * a + 1]);
}

void ActDot(const mjModel* m, mjData* d, int instance) {
  const mjtNum* u = HeldControls(m, d, instance);
  for (int a = 0; a < m->nu; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] == 0) continue;
    const int adr = m->actuator_actadr[a] + m->actuator_actnum[a] - 1;
    const mjtNum tau = mju_max(mjMINVAL, m->actuator_dynprm[mjNDYN * a]);
    d->act_dot[adr] = (Clamped(m, a, u[a]) - d->act[adr]) / tau;
  }
}

void Compute(const mjModel* m, mjData* d, int instance, int) {
  const mjtNum* u = HeldControls(m, d, instance);
  for (int a = 0; a < m->nu; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] != 0) continue;
    mjtNum force = m->actuator_gainprm[mjNGAIN * a] * Clamped(m, a, u[a]);
    force += 0.0;  // MuJoCo adds the (zero) bias of a biastype="none" actuator
    d->actuator_force[a] = force;
  }
}

void Advance(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  state[1] = state[0];
}

void Copy(mjData* dest, const mjModel* m, const mjData* src, int instance) {
  (void)src;
  // A copy flies on with a host of its own, from the model (our plugins cannot be cloned).
  dest->plugin_data[instance] = 0;
  Init(m, dest, instance);
}

}  // namespace

void RegisterSwarmPlugin() {
  static const std::vector<const char*> kAttributes = AttributeNames();
  mjpPlugin plugin;
  mjp_defaultPlugin(&plugin);
  plugin.name = kName;
  plugin.nattribute = static_cast<int>(kAttributes.size());
  plugin.attributes = kAttributes.data();
  plugin.capabilityflags = mjPLUGIN_ACTUATOR;
  plugin.nstate = NState;
  plugin.init = Init;
  plugin.destroy = Destroy;
  plugin.copy = Copy;
  plugin.reset = Reset;
  plugin.compute = Compute;
  plugin.advance = Advance;
  plugin.actuator_act_dot = ActDot;
  mjp_registerPlugin(&plugin);
}

}  // namespace mjf::native
