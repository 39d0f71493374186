// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation's native MuJoCo engine plugins (mjpPlugin), thin adapters over the bridges to our
// own plugin ABI:
//   mjformation.swarm     flies every vehicle of an exported experiment (SwarmHost: the leader's
//                         guidance, the formation law, one attitude instance per vehicle);
//   mjformation.attitude  flies one vehicle of any model with a guidance and an attitude plugin
//                         of ours (VehicleHost): a Menagerie-style drone in the user's scene.
// Both are actuator plugins with the same timing and actuation, described here.
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
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "swarm_host.hpp"
#include "vehicle_host.hpp"

namespace mjf::native {
namespace {

// State: [0] the physics step whose controls are held (-1: none), [1] the last committed step,
// [2 + a] the held control of actuator a (NaN: not driven by this instance).
constexpr int kHeader = 2;

// What an instance holds in plugin_data: its bridge, rebuilt on reset.
struct Holder {
  virtual ~Holder() = default;
  virtual void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls) = 0;
  virtual void Restart(const mjModel* m, int instance) = 0;
};

std::string InstanceWhere(const char* plugin, const mjModel* m, int instance) {
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  return std::string("MJCF plugin '") + plugin + "' instance '" +
         (name && name[0] ? name : std::to_string(instance)) + "'";
}

// Builds on a thread of its own. A bridge may load a vehicle model (a compile of its own), and
// MuJoCo keeps the compiler's error jump per thread: a compile nested on the compiling thread
// would leave the outer compile's jump pointing into a finished frame.
template <typename Make>
auto OnOwnThread(Make make) -> decltype(make()) {
  decltype(make()) made;
  std::exception_ptr failure;
  std::thread builder([&] {
    try {
      made = make();
    } catch (...) {
      failure = std::current_exception();
    }
  });
  builder.join();
  if (failure) std::rethrow_exception(failure);
  return made;
}

// ---- mjformation.swarm
constexpr char kSwarm[] = "mjformation.swarm";

runner::ExperimentConfig ReadSwarmConfig(const mjModel* m, int instance) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& key : CarriedSections()) {
    const char* value = mj_getPluginConfig(m, instance, key.c_str());
    pairs.emplace_back(key, value ? value : "");
  }
  return ConfigFromPairs(pairs, InstanceWhere(kSwarm, m, instance));
}

struct SwarmHolder final : Holder {
  std::unique_ptr<SwarmHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls) override {
    host->Tick(step, m, d, controls);
  }
  void Restart(const mjModel* m, int) override { host->Restart(m); }
};

std::unique_ptr<Holder> MakeSwarm(const mjModel* m, int instance) {
  auto holder = std::make_unique<SwarmHolder>();
  holder->host =
      OnOwnThread([&] { return std::make_unique<SwarmHost>(m, ReadSwarmConfig(m, instance)); });
  return holder;
}

// The experiment parser checks every section while the model compiles (names, values,
// messages as for an experiment file); our plugins' create() checks their attributes in Init,
// which the compiler also runs on a trial mjData.
void CheckSwarm(const mjModel* m, int instance) { ReadSwarmConfig(m, instance); }

// ---- mjformation.attitude
constexpr char kAttitude[] = "mjformation.attitude";

struct VehicleHolder final : Holder {
  std::unique_ptr<VehicleHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls) override {
    host->Tick(step, m, d, controls);
  }
  void Restart(const mjModel* m, int instance) override {
    host.reset();
    host = std::make_unique<VehicleHost>(m, VehicleConfigFromModel(m, instance, kAttitude));
  }
};

std::unique_ptr<Holder> MakeVehicle(const mjModel* m, int instance) {
  auto holder = std::make_unique<VehicleHolder>();
  holder->host = OnOwnThread([&] {
    return std::make_unique<VehicleHost>(m, VehicleConfigFromModel(m, instance, kAttitude));
  });
  return holder;
}

void CheckVehicle(const mjModel* m, int instance) {
  VehicleConfigFromModel(m, instance, kAttitude);
}

// ---- the shared mechanics, one set of callbacks per plugin

// Runs `body` and raises what it throws as MuJoCo's error. mju_error does not return: MuJoCo's
// handler longjmp()s (the compiler's) or exits, so no C++ object may be alive in this frame
// when it is called; the message waits in a plain buffer.
template <typename Body>
void ErrorFromException(Body body) {
  char message[1024] = {0};
  try {
    body();
  } catch (const std::exception& e) {
    std::snprintf(message, sizeof(message), "%s", e.what());
  }
  if (message[0]) mju_error("%s", message);
}

struct Kind {
  const char* name;
  std::unique_ptr<Holder> (*make)(const mjModel*, int);
  void (*check)(const mjModel*, int);
};

// Called while the model compiles: a refusal becomes the compile error (mju_error inside the
// compiler here; in Init, mju_warning + -1, which MuJoCo appends to its error).
template <const Kind& K>
int NState(const mjModel* m, int instance) {
  ErrorFromException([&] { K.check(m, instance); });
  return kHeader + m->nu;
}

void ClearState(const mjModel* m, mjtNum* state) {
  state[0] = -1;
  state[1] = -1;
  for (int a = 0; a < m->nu; ++a) state[kHeader + a] = std::numeric_limits<double>::quiet_NaN();
}

Holder* HolderOf(const mjData* d, int instance) {
  return reinterpret_cast<Holder*>(d->plugin_data[instance]);
}

template <const Kind& K>
int Init(const mjModel* m, mjData* d, int instance) {
  try {
    d->plugin_data[instance] = reinterpret_cast<uintptr_t>(K.make(m, instance).release());
  } catch (const std::exception& e) {
    mju_warning("%s", e.what());
    return -1;
  }
  ClearState(m, d->plugin_state + m->plugin_stateadr[instance]);
  return 0;
}

void Destroy(mjData* d, int instance) {
  delete HolderOf(d, instance);
  d->plugin_data[instance] = 0;
}

// Our plugins' own state cannot be rewound, so a reset builds the bridge again from the model.
template <const Kind& K>
void Reset(const mjModel* m, mjtNum* plugin_state, void* plugin_data, int instance) {
  ClearState(m, plugin_state);
  if (!plugin_data) return;  // mj_makeData resets before init
  ErrorFromException([&] { static_cast<Holder*>(plugin_data)->Restart(m, instance); });
}

mjtNum* State(const mjModel* m, mjData* d, int instance) {
  return d->plugin_state + m->plugin_stateadr[instance];
}

// The tick of the current step, once (see the file comment).
template <const Kind& K>
mjtNum* HeldControls(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  // The step index of d->time (accumulated by MuJoCo, so within rounding of k * timestep);
  // an intermediate stage of RK4 (t + h/2) belongs to its step.
  const int64_t step = static_cast<int64_t>(std::floor(d->time / m->opt.timestep + 1e-3));
  if (state[0] != static_cast<double>(step)) {
    ErrorFromException([&] { HolderOf(d, instance)->Tick(step, m, d, state + kHeader); });
    state[0] = static_cast<double>(step);
  }
  return state + kHeader;
}

double Clamped(const mjModel* m, int a, double u) {
  if (!m->actuator_ctrllimited[a]) return u;
  return mju_clip(u, m->actuator_ctrlrange[2 * a], m->actuator_ctrlrange[2 * a + 1]);
}

template <const Kind& K>
void ActDot(const mjModel* m, mjData* d, int instance) {
  const mjtNum* u = HeldControls<K>(m, d, instance);
  for (int a = 0; a < m->nu; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] == 0) continue;
    const int adr = m->actuator_actadr[a] + m->actuator_actnum[a] - 1;
    const mjtNum tau = mju_max(mjMINVAL, m->actuator_dynprm[mjNDYN * a]);
    d->act_dot[adr] = (Clamped(m, a, u[a]) - d->act[adr]) / tau;
  }
}

template <const Kind& K>
void Compute(const mjModel* m, mjData* d, int instance, int) {
  const mjtNum* u = HeldControls<K>(m, d, instance);
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

// A copy flies on with a bridge of its own, built from the model (ours cannot be cloned), and
// the source's held controls and step.
template <const Kind& K>
void Copy(mjData* dest, const mjModel* m, const mjData* src, int instance) {
  (void)src;
  dest->plugin_data[instance] = 0;
  Init<K>(m, dest, instance);
}

template <const Kind& K>
void Register(const std::vector<const char*>& attributes) {
  mjpPlugin plugin;
  mjp_defaultPlugin(&plugin);
  plugin.name = K.name;
  plugin.nattribute = static_cast<int>(attributes.size());
  plugin.attributes = attributes.data();
  plugin.capabilityflags = mjPLUGIN_ACTUATOR;
  plugin.nstate = NState<K>;
  plugin.init = Init<K>;
  plugin.destroy = Destroy;
  plugin.copy = Copy<K>;
  plugin.reset = Reset<K>;
  plugin.compute = Compute<K>;
  plugin.advance = Advance;
  plugin.actuator_act_dot = ActDot<K>;
  mjp_registerPlugin(&plugin);
}

constexpr Kind kSwarmKind = {kSwarm, MakeSwarm, CheckSwarm};
constexpr Kind kAttitudeKind = {kAttitude, MakeVehicle, CheckVehicle};

}  // namespace

void RegisterPlugins() {
  static const std::vector<const char*> kSwarmAttributes = [] {
    std::vector<const char*> names;
    for (const std::string& key : CarriedSections()) names.push_back(key.c_str());
    return names;
  }();
  Register<kSwarmKind>(kSwarmAttributes);
  Register<kAttitudeKind>(VehicleAttributes());
}

}  // namespace mjf::native
