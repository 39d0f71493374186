// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// mjformation's native MuJoCo engine plugins (mjpPlugin), thin adapters over the bridges to our
// own plugin ABI:
//   mjformation.swarm     flies every vehicle of an exported experiment (SwarmHost: the leader's
//                         guidance, the formation law, one attitude instance per vehicle);
//   mjformation.attitude  flies one vehicle of any model with a guidance and an attitude plugin
//                         of ours (VehicleHost): a Menagerie-style drone in the user's scene.
// Both are actuator plugins with the same timing and actuation, described here. Both declare
// the passive capability too, so that a body may reference an instance (MuJoCo's attach keeps
// only the instances an attached element references, and the bodies referencing an instance
// tell the names an attach gave its vehicles, attach_names.hpp), and so that the swarm knows
// when qfrc_passive is recomputed (see Compute: its forces besides the actuators).
//
// Timing and state (the tick rule, docs/PLUGINS.md). MuJoCo calls actuator plugins inside
// mj_fwdActuation, after every position and velocity sensor of the step: the same sensor values
// the runner reads between mj_step1 and mj_step2. All of the controllers' state lives in
// plugin_state, so MuJoCo copies, saves (mj_getState) and restores it with the physics:
//   [0] layout (kLayout), [1] k = the steps committed (advance adds 1), [2] the step whose
//   controls are held (-1: none), [3] 1 when the blocks below hold a state (0 after a reset:
//   the controllers' initial state), [4] 1 while qfrc_passive is recomputed and the held forces
//   are not yet added to it (see Compute), [5 + a] the held control of actuator id a (NaN: not
//   driven; one slot per actuator, nactuator of them: in MuJoCo 4 an actuator may take several
//   controls, so nu is not the actuator count), then the held forces' block (Holder::held_size:
//   SwarmHost::held_size, the wind's drag and the wrench rotor model's controls and motor lags;
//   zeros after a reset), then the state blocks (SwarmHost::GetState: the tick's,
//   runner::ControlTick::GetState, ABI 4, then the force stages'). Layout 2; layout 1 had
//   neither the mark nor the held forces.
// The tick of step k runs at the first evaluation of step k (held != k), from the blocks, and
// leaves the controls and the new blocks with held = k. Every further evaluation of the same
// step (RK4's stages, mjd_transitionFD's perturbed evaluations restored to the same state,
// mj_forward again and again) reuses the held controls and advances nothing; advance() commits
// (k + 1). The time a controller sees is k * timestep, never d->time. plugin_data is a cache
// (the plugin instances), rebuilt from the model's configuration and loaded from the blocks
// before each tick: compute depends on the model and mjData only.
//
// Actuation. The runner writes its controls into d->ctrl; MuJoCo then clamps them to
// ctrlrange and, for a filter actuator, sets act_dot = (ctrl - act) / max(mjMINVAL, tau), and
// for an actuator without activation, force = gain * ctrl. This plugin writes the same two
// quantities, with the same operations, from its held controls: in actuator_act_dot (called
// after MuJoCo's own act_dot) and in compute (called after MuJoCo's own forces). The
// vehicles' actuators keep their MJCF definitions.
// ctrl as an input: d->ctrl of a driven actuator is an additive trim on the controllers'
// command, applied before the clamp: u = clamp(u_controller + ctrl). MuJoCo's default ctrl = 0
// flies the runner's flight bit for bit (a zero trim is not added at all: see Applied). The
// trim is read at every evaluation, not held at the tick: the controllers still tick once per
// committed step and never see it, so mujoco.rollout's `control` and the viewer's sliders act
// from the step they are set, and mjd_transitionFD's B is d(next state)/d(trim) through the
// plant with the step's command fixed, the closed loop's B (the controllers answer from the
// next tick on, through A). A bad control (mjWARN_BADCTRL) zeroes every trim, as MuJoCo zeroes
// every control.
// Per-actuator arrays are indexed by actuator id, per-control arrays (ctrlrange, ctrllimited)
// by the actuator's actuator_ctrladr, per-output arrays (actuator_force) by its
// actuator_outadr; only single-control, single-output actuators are driven.
#include <mujoco/mjplugin.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "attach_names.hpp"
#include "mjformation/scene/scene.hpp"
#include "scene_files.hpp"
#include "swarm_host.hpp"
#include "vehicle_host.hpp"

namespace mjf::native {
namespace {

constexpr int kLayout = 0, kCommitted = 1, kHeld = 2, kValid = 3, kPassive = 4, kHeader = 5;
constexpr double kLayoutVersion = 2;

// What an instance caches in plugin_data: its plugin instances and their initial state.
struct Holder {
  virtual ~Holder() = default;
  virtual void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls,
                    double* held) = 0;
  // The forces besides the actuators' (SwarmHost::held_size; none for mjformation.attitude).
  virtual size_t held_size() const { return 0; }
  virtual void AddForces(const mjModel*, mjData*, const double*) {}
  virtual void Advance(const mjModel*, double*) {}
  virtual size_t state_size() const = 0;
  virtual void GetState(double* out) const = 0;
  virtual void SetState(const double* in) = 0;
  std::vector<double> initial;  // the state before the first tick (what a reset restores)
};

std::string InstanceName(const mjModel* m, int instance) {
  const char* name = mj_id2name(m, mjOBJ_PLUGIN, instance);
  return name && name[0] ? name : std::to_string(instance);
}

std::string InstanceWhere(const char* plugin, const mjModel* m, int instance) {
  return std::string("MJCF plugin '") + plugin + "' instance '" + InstanceName(m, instance) + "'";
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

// Which holder belongs to which mjData. MuJoCo copies plugin_data raw in places (an unpickled
// MjData, mj_copyData before our copy callback runs), so a pointer found there is trusted only
// when this table says it is that mjData's own.
class Holders {
 public:
  static Holders& Get() {
    static Holders holders;  // process-wide: mjData pointers are
    return holders;
  }
  Holder* Find(const mjData* d, int instance) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = owned_.find({d, instance});
    return it == owned_.end() ? nullptr : it->second.get();
  }
  // Takes `holder` as d's (the one it had before is freed) and returns it.
  Holder* Adopt(const mjData* d, int instance, std::unique_ptr<Holder> holder) {
    std::unique_ptr<Holder> old;
    std::lock_guard<std::mutex> lock(mutex_);
    std::unique_ptr<Holder>& slot = owned_[{d, instance}];
    old = std::move(slot);
    slot = std::move(holder);
    return slot.get();
  }
  std::unique_ptr<Holder> Release(const mjData* d, int instance) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = owned_.find({d, instance});
    if (it == owned_.end()) return nullptr;
    std::unique_ptr<Holder> holder = std::move(it->second);
    owned_.erase(it);
    return holder;
  }

 private:
  std::mutex mutex_;
  std::map<std::pair<const mjData*, int>, std::unique_ptr<Holder>> owned_;
};

// ---- mjformation.swarm
constexpr char kSwarm[] = "mjformation.swarm";

runner::ExperimentConfig ReadSwarmConfig(const mjModel* m, int instance) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& key : CarriedSections()) {
    const char* value = mj_getPluginConfig(m, instance, key.c_str());
    pairs.emplace_back(key, value ? value : "");
  }
  return ConfigFromPairs(pairs, InstanceWhere(kSwarm, m, instance), SceneFolder(m, instance));
}

// The vehicles' bodies as the exported scene names them (runner::VehiclePrefix), 0 = leader.
std::vector<std::string> SwarmBodies(int followers) {
  std::vector<std::string> bodies;
  for (int i = 0; i <= followers; ++i) {
    bodies.push_back(runner::VehiclePrefix(i) + "vehicle");
  }
  return bodies;
}

// How the swarm's names read in `m`: as exported, or renamed by an attach (attach_names.hpp).
runner::SceneNames SwarmNames(const mjModel* m, int instance,
                              const runner::ExperimentConfig& config) {
  return InstanceNames(m, instance, SwarmBodies(config.followers),
                       InstanceWhere(kSwarm, m, instance));
}

// What one model's swarm instances share (the files read, the libraries loaded), kept per
// model so that a new mjData, a copy or a reset reads nothing again. Keyed by the model's
// address and what the instance is made of (its configuration, sizes and timestep), so a later
// model at the same address is not mistaken for it.
class SwarmModels {
 public:
  static SwarmModels& Get() {
    static SwarmModels models;
    return models;
  }
  std::shared_ptr<const SwarmShared> For(const mjModel* m, int instance) {
    const std::string key = Key(m, instance);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const Entry& e : entries_) {
        if (e.model == m && e.instance == instance && e.key == key) return e.shared;
      }
    }
    const runner::ExperimentConfig config = ReadSwarmConfig(m, instance);
    const runner::SceneNames names = SwarmNames(m, instance, config);
    std::shared_ptr<const SwarmShared> shared =
        OnOwnThread([&] { return SwarmHost::Prepare(m, config, true, names); });
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back({m, instance, key, shared});
    if (entries_.size() > kKept) entries_.erase(entries_.begin());
    return shared;
  }

 private:
  static constexpr size_t kKept = 16;  // models alive at once in one process, generously
  static std::string Key(const mjModel* m, int instance) {
    std::string key =
        std::to_string(m->nu) + "/" + std::to_string(m->nsensor) + "/" + std::to_string(m->nbody) +
        "/" + std::to_string(m->opt.timestep) + "\n" +
        SceneFolder(m, instance);  // the same scene from another folder reads other files
    for (const std::string& section : CarriedSections()) {
      const char* value = mj_getPluginConfig(m, instance, section.c_str());
      key += "\n" + section + "=" + (value ? value : "");
    }
    return key;
  }
  struct Entry {
    const mjModel* model;
    int instance;
    std::string key;
    std::shared_ptr<const SwarmShared> shared;
  };
  std::mutex mutex_;
  std::vector<Entry> entries_;
};

struct SwarmHolder final : Holder {
  std::unique_ptr<SwarmHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls,
            double* held) override {
    host->Tick(step, m, d, controls, held);
  }
  size_t held_size() const override { return host->held_size(); }
  void AddForces(const mjModel* m, mjData* d, const double* held) override {
    host->AddForces(m, d, held);
  }
  void Advance(const mjModel* m, double* held) override { host->Advance(m, held); }
  size_t state_size() const override { return host->state_size(); }
  void GetState(double* out) const override { host->GetState(out); }
  void SetState(const double* in) override { host->SetState(in); }
};

std::unique_ptr<Holder> MakeSwarm(const mjModel* m, int instance) {
  auto holder = std::make_unique<SwarmHolder>();
  holder->host = std::make_unique<SwarmHost>(SwarmModels::Get().For(m, instance));
  return holder;
}

// The state's size, while the model compiles: its sensors and actuators are not there yet, so
// the plugins are created on the vehicles' description alone (runner::DescribeVehicles). The
// experiment parser checks every section here too (names, values, messages as for a file), and
// the bodies referencing the instance are checked to be its vehicles' (SwarmNames).
size_t SwarmStateSize(const mjModel* m, int instance) {
  const runner::ExperimentConfig config = ReadSwarmConfig(m, instance);
  SwarmNames(m, instance, config);
  const std::unique_ptr<SwarmHost> host = OnOwnThread(
      [&] { return std::make_unique<SwarmHost>(SwarmHost::Prepare(m, config, false)); });
  return host->held_size() + host->state_size();
}

// ---- mjformation.attitude
constexpr char kAttitude[] = "mjformation.attitude";
// The state a vehicle's guidance and attitude plugins may declare together, in doubles: a
// fixed bound, since the vehicle's actuators (which their create() reads) are not compiled when
// MuJoCo asks for the size. The stock plugins declare at most a few tens.
constexpr size_t kVehicleStateBound = 256;

struct VehicleHolder final : Holder {
  std::unique_ptr<VehicleHost> host;
  void Tick(int64_t step, const mjModel* m, const mjData* d, double* controls, double*) override {
    host->Tick(step, m, d, controls);
  }
  size_t state_size() const override { return kVehicleStateBound; }
  void GetState(double* out) const override {
    std::fill(out, out + kVehicleStateBound, 0.0);
    host->GetState(out);
  }
  void SetState(const double* in) override { host->SetState(in); }
};

// The instance's configuration with its body and actuators named as they read in `m`: as
// written, or renamed by an attach, read from the body that references the instance
// (attach_names.hpp).
VehicleHostConfig VehicleConfig(const mjModel* m, int instance) {
  VehicleHostConfig c = VehicleConfigFromModel(m, instance, kAttitude);
  const runner::SceneNames names = InstanceNames(m, instance, {c.body}, c.where);
  c.body = names(c.body);
  for (std::string& actuator : c.actuators) actuator = names(actuator);
  return c;
}

std::unique_ptr<Holder> MakeVehicle(const mjModel* m, int instance) {
  auto holder = std::make_unique<VehicleHolder>();
  holder->host =
      OnOwnThread([&] { return std::make_unique<VehicleHost>(m, VehicleConfig(m, instance)); });
  if (holder->host->state_size() > kVehicleStateBound) {
    throw std::runtime_error(InstanceWhere(kAttitude, m, instance) + ": its plugins declare " +
                             std::to_string(holder->host->state_size()) +
                             " doubles of state, more than the " +
                             std::to_string(kVehicleStateBound) + " this plugin holds");
  }
  return holder;
}

size_t VehicleStateSize(const mjModel* m, int instance) {
  VehicleConfig(m, instance);
  return kVehicleStateBound;
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
  size_t (*state_size)(const mjModel*, int);
};

bool IsSwarm(const mjModel* m, int instance) {
  const mjpPlugin* kind = mjp_getPluginAtSlot(m->plugin[instance]);
  return kind && std::string(kind->name) == kSwarm;
}

// What an instance flies, by the names in `m` (after any attach): a swarm its vehicles' bodies,
// an attitude instance its body and actuators.
struct Driven {
  bool swarm = false;
  std::vector<std::string> bodies, actuators;
};

// Null for an instance of a plugin other than ours.
std::unique_ptr<Driven> DrivenBy(const mjModel* m, int instance) {
  const mjpPlugin* kind = mjp_getPluginAtSlot(m->plugin[instance]);
  auto driven = std::make_unique<Driven>();
  if (IsSwarm(m, instance)) {
    const runner::ExperimentConfig config = ReadSwarmConfig(m, instance);
    const runner::SceneNames names = SwarmNames(m, instance, config);
    driven->swarm = true;
    for (const std::string& body : SwarmBodies(config.followers)) {
      driven->bodies.push_back(names(body));
    }
  } else if (kind && std::string(kind->name) == kAttitude) {
    const VehicleHostConfig c = VehicleConfig(m, instance);
    driven->bodies = {c.body};
    driven->actuators = c.actuators;
  } else {
    return nullptr;
  }
  return driven;
}

// A swarm's affixes without its configuration (as many vehicles as bodies reference it), so that
// two swarms on one set of vehicles are named as such before either's configuration is read;
// nullopt when they do not resolve (SwarmNames then words the refusal).
std::optional<runner::SceneNames> SwarmAffixes(const mjModel* m, int instance) {
  int referencing = 0;
  for (int b = 1; b < m->nbody; ++b) referencing += m->body_plugin[b] == instance;
  try {
    return InstanceNames(m, instance, SwarmBodies(std::max(referencing, 1) - 1), "");
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

std::runtime_error SecondSwarm(const mjModel* m, int instance, int other, const std::string& body) {
  return std::runtime_error(InstanceWhere(kSwarm, m, instance) + ": a second swarm instance ('" +
                            InstanceName(m, other) + "' is the other) flies the same vehicles ('" +
                            body + "'); remove one of them, or attach each copy under a prefix " +
                            "of its own");
}

// Two swarm instances whose vehicles carry the same affixes fly the same vehicles.
void RefuseSecondSwarm(const mjModel* m, int instance) {
  const std::optional<runner::SceneNames> mine = SwarmAffixes(m, instance);
  for (int other = 0; mine && other < m->nplugin; ++other) {
    if (other == instance || !IsSwarm(m, other)) continue;
    const std::optional<runner::SceneNames> theirs = SwarmAffixes(m, other);
    if (!theirs || theirs->prefix != mine->prefix || theirs->suffix != mine->suffix) continue;
    throw SecondSwarm(m, instance, other, (*mine)(SwarmBodies(0)[0]));
  }
}

std::string Shared(const std::vector<std::string>& mine, const std::vector<std::string>& theirs) {
  for (const std::string& name : mine) {
    if (std::find(theirs.begin(), theirs.end(), name) != theirs.end()) return name;
  }
  return "";
}

// No vehicle driven twice, refused while the model compiles: no two swarms fly the same
// vehicles (two attached copies under their own prefixes fly their own), no actuator is named by
// two attitude instances and no body is flown by two instances (the later instance's controls
// would silently replace the earlier's).
void RefuseDrivingTwice(const char* plugin, const mjModel* m, int instance) {
  if (IsSwarm(m, instance)) RefuseSecondSwarm(m, instance);
  const std::unique_ptr<Driven> mine = DrivenBy(m, instance);
  for (int other = 0; mine && other < m->nplugin; ++other) {
    const std::unique_ptr<Driven> theirs = other == instance ? nullptr : DrivenBy(m, other);
    if (!theirs) continue;
    const std::string actuator = Shared(mine->actuators, theirs->actuators);
    if (!actuator.empty()) {
      throw std::runtime_error(InstanceWhere(plugin, m, instance) +
                               ": <config key=\"actuators\">: '" + actuator +
                               "' is driven by instance '" + InstanceName(m, other) +
                               "' too; an actuator takes one instance's controls");
    }
    const std::string body = Shared(mine->bodies, theirs->bodies);
    if (body.empty()) continue;
    if (mine->swarm && theirs->swarm) throw SecondSwarm(m, instance, other, body);
    throw std::runtime_error(InstanceWhere(plugin, m, instance) + ": body '" + body +
                             "' is flown by instance '" + InstanceName(m, other) +
                             "' too; a vehicle takes one instance's controls");
  }
}

// Called while the model compiles: a refusal becomes the compile error.
template <const Kind& K>
int NState(const mjModel* m, int instance) {
  size_t blocks = 0;
  ErrorFromException([&] {
    RefuseDrivingTwice(K.name, m, instance);
    blocks = K.state_size(m, instance);
  });
  return kHeader + static_cast<int>(m->nactuator + blocks);
}

mjtNum* State(const mjModel* m, mjData* d, int instance) {
  return d->plugin_state + m->plugin_stateadr[instance];
}

// The state before the first step. The held forces' block becomes zeros (motor lags at rest);
// the tick's blocks are not read while [kValid] is 0.
void ClearState(const mjModel* m, int instance, mjtNum* state) {
  state[kLayout] = kLayoutVersion;
  state[kCommitted] = 0;
  state[kHeld] = -1;
  state[kValid] = 0;
  state[kPassive] = 0;
  for (int a = 0; a < m->nactuator; ++a) {
    state[kHeader + a] = std::numeric_limits<double>::quiet_NaN();
  }
  std::fill(state + kHeader + m->nactuator, state + m->plugin_statenum[instance], 0.0);
}

// d's holder: its own, or one built for it (a copy, an unpickled MjData, a failed build
// before). Never a pointer that plugin_data holds but the table does not give to d.
template <const Kind& K>
Holder* HolderFor(const mjModel* m, mjData* d, int instance) {
  Holder* holder = Holders::Get().Find(d, instance);
  if (!holder) {
    std::unique_ptr<Holder> made = K.make(m, instance);
    made->initial.resize(made->state_size());
    made->GetState(made->initial.data());
    holder = Holders::Get().Adopt(d, instance, std::move(made));
  }
  d->plugin_data[instance] = reinterpret_cast<uintptr_t>(holder);
  return holder;
}

template <const Kind& K>
int Init(const mjModel* m, mjData* d, int instance) {
  try {
    HolderFor<K>(m, d, instance);
  } catch (const std::exception& e) {
    // MuJoCo's own error names only the plugin's slot: the warning names the instance.
    const std::string where = InstanceWhere(K.name, m, instance);
    const std::string message = e.what();
    mju_warning("%s",
                message.rfind(where, 0) == 0 ? message.c_str() : (where + ": " + message).c_str());
    return -1;
  }
  ClearState(m, instance, State(m, d, instance));
  return 0;
}

void Destroy(mjData* d, int instance) {
  Holders::Get().Release(d, instance);  // frees it; a raw copy of another's pointer is not ours
  d->plugin_data[instance] = 0;
}

// A reset only clears plugin_state: the next tick starts from the holder's initial state.
// Nothing is rebuilt, no file is read.
void Reset(const mjModel* m, mjtNum* plugin_state, void*, int instance) {
  ClearState(m, instance, plugin_state);
}

// The tick of the current step, once (see the file comment).
template <const Kind& K>
mjtNum* HeldControls(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  mjtNum* controls = state + kHeader;
  if (state[kHeld] == state[kCommitted]) return controls;
  ErrorFromException([&] {
    if (state[kLayout] != kLayoutVersion) {
      throw std::runtime_error(InstanceWhere(K.name, m, instance) + ": plugin_state has layout " +
                               std::to_string(state[kLayout]) + ", this library reads layout " +
                               std::to_string(kLayoutVersion) +
                               " (a state saved by another version, or never initialised)");
    }
    Holder* holder = HolderFor<K>(m, d, instance);
    mjtNum* held = controls + m->nactuator;
    mjtNum* blocks = held + holder->held_size();
    holder->SetState(state[kValid] != 0 ? blocks : holder->initial.data());
    const auto step = static_cast<int64_t>(state[kCommitted]);
    holder->Tick(step, m, d, controls, held);
    holder->GetState(blocks);
    state[kValid] = 1;
    state[kHeld] = state[kCommitted];
  });
  return controls;
}

// u clamped to actuator a's ctrlrange: ctrllimited and ctrlrange are per control (nu rows).
double Clamped(const mjModel* m, int a, double u) {
  const int c = m->actuator_ctrladr[a];
  if (!m->actuator_ctrllimited[c]) return u;
  return mju_clip(u, m->actuator_ctrlrange[2 * c], m->actuator_ctrlrange[2 * c + 1]);
}

// Whether MuJoCo zeroes every control of this evaluation: it does when any control, clamped
// (unless clamping is disabled), is bad (NaN, or past mjMAXVAL), with its warning
// mjWARN_BADCTRL (mj_fwdActuation); the trims follow the same rule.
bool ControlsBad(const mjModel* m, const mjData* d) {
  const bool clamp = !(m->opt.disableflags & mjDSBL_CLAMPCTRL);
  for (int c = 0; c < m->nu; ++c) {
    mjtNum u = d->ctrl[c];
    if (clamp && m->actuator_ctrllimited[c]) {
      u = mju_clip(u, m->actuator_ctrlrange[2 * c], m->actuator_ctrlrange[2 * c + 1]);
    }
    if (mju_isBad(u)) return true;
  }
  return false;
}

// What actuator a applies: the held command plus the user's trim d->ctrl, clamped
// (u = clamp(u_controller + ctrl), the file comment's "Actuation"). Read at every evaluation,
// so a trim acts through the plant with the controllers' command of the step fixed.
double Applied(const mjModel* m, const mjData* d, bool bad, int a, double held) {
  const mjtNum trim = bad ? 0 : d->ctrl[m->actuator_ctrladr[a]];
  // Added only when non-zero: held + 0.0 turns a held -0.0 into +0.0, the clamp keeps either
  // sign (0 lies in a range from 0) and act_dot = (u - act) / tau carries it, so ctrl = 0 must
  // skip the sum to be the runner's bits.
  return Clamped(m, a, trim != 0 ? held + trim : held);
}

template <const Kind& K>
void ActDot(const mjModel* m, mjData* d, int instance) {
  const mjtNum* u = HeldControls<K>(m, d, instance);
  const bool bad = ControlsBad(m, d);
  for (int a = 0; a < m->nactuator; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] == 0) continue;
    const int adr = m->actuator_actadr[a] + m->actuator_actnum[a] - 1;
    const mjtNum tau = mju_max(mjMINVAL, m->actuator_dynprm[mjNDYN * a]);
    d->act_dot[adr] = (Applied(m, d, bad, a, u[a]) - d->act[adr]) / tau;
  }
}

// The step's forces besides the actuators' ([wind], the wrench rotor model) into qfrc_passive,
// once per recomputation of qfrc_passive (see Compute).
template <const Kind& K>
void AddHeldForces(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  if (state[kPassive] == 0) return;
  state[kPassive] = 0;
  ErrorFromException([&] {
    Holder* holder = HolderFor<K>(m, d, instance);
    if (holder->held_size()) holder->AddForces(m, d, state + kHeader + m->nactuator);
  });
}

// The passive stage marks qfrc_passive as recomputed (mj_passive has just cleared and summed
// it); the actuation stage, after the tick, adds the held forces into it and clears the mark.
// Forces go into qfrc_passive, not qfrc_applied (the user's input, and part of the state):
// MuJoCo sums qfrc_smooth = passive - bias + applied + actuator, and with no spring or damper
// passive is +0 where the runner's qfrc_applied was, so the sums are the runner's bits (the
// runner adds them into qfrc_passive too, after mj_step1). An evaluation that skips the
// velocity stage (mjd_transitionFD's control and activation columns, mj_forwardSkip) keeps the
// qfrc_passive of the evaluation before it, forces included: without the mark they would be
// added twice.
template <const Kind& K>
void Compute(const mjModel* m, mjData* d, int instance, int capability) {
  if (capability == mjPLUGIN_PASSIVE) {
    State(m, d, instance)[kPassive] = 1;
    return;
  }
  if (capability != mjPLUGIN_ACTUATOR) return;
  const mjtNum* u = HeldControls<K>(m, d, instance);
  const bool bad = ControlsBad(m, d);
  for (int a = 0; a < m->nactuator; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] != 0) continue;
    mjtNum force = m->actuator_gainprm[mjNGAIN * a] * Applied(m, d, bad, a, u[a]);
    // Not dead: MuJoCo computes gain * ctrl + bias, and the (zero) bias of a biastype="none"
    // actuator turns a -0.0 force into +0.0. The same bits as the runner's need the same sum.
    force += 0.0;
    d->actuator_force[m->actuator_outadr[a]] = force;
  }
  AddHeldForces<K>(m, d, instance);
}

// The commit: the step whose tick ran is done, and the motor lags of the wrench rotor model
// follow its controls (the runner's Actuation::Advance after mj_step2).
template <const Kind& K>
void Advance(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  if (state[kHeld] == state[kCommitted]) {
    ErrorFromException([&] {
      Holder* holder = HolderFor<K>(m, d, instance);
      if (holder->held_size()) holder->Advance(m, state + kHeader + m->nactuator);
    });
  }
  state[kCommitted] += 1;
}

// The copy's state came with plugin_state; dest keeps the holder it had (a viewer copying
// every frame into one mjData builds nothing) or gets one at its first tick.
template <const Kind& K>
void Copy(mjData* dest, const mjModel*, const mjData*, int instance) {
  Holder* own = Holders::Get().Find(dest, instance);
  dest->plugin_data[instance] = reinterpret_cast<uintptr_t>(own);
}

template <const Kind& K>
void Register(const std::vector<const char*>& attributes) {
  // Another copy of this library loaded first (the build tree's and an installed one, or a copy
  // beside a moved scene) has registered the name: that copy flies, and MuJoCo would refuse a
  // second registration of the name with other callbacks.
  int slot = -1;
  if (mjp_getPlugin(K.name, &slot)) return;
  mjpPlugin plugin;
  mjp_defaultPlugin(&plugin);
  plugin.name = K.name;
  plugin.nattribute = static_cast<int>(attributes.size());
  plugin.attributes = attributes.data();
  // Passive too: MuJoCo lets a body reference only a passive plugin's instance, and an instance
  // that no element of an attached tree references is dropped by mjs_attach (the exported
  // vehicles' bodies reference theirs, attach_names.hpp); and the passive callback marks
  // qfrc_passive recomputed (Compute). The forces themselves are added in the actuation stage,
  // after the tick.
  plugin.capabilityflags = mjPLUGIN_ACTUATOR | mjPLUGIN_PASSIVE;
  plugin.nstate = NState<K>;
  plugin.init = Init<K>;
  plugin.destroy = Destroy;
  plugin.copy = Copy<K>;
  plugin.reset = Reset;
  plugin.compute = Compute<K>;
  plugin.advance = Advance<K>;
  plugin.actuator_act_dot = ActDot<K>;
  mjp_registerPlugin(&plugin);
}

constexpr Kind kSwarmKind = {kSwarm, MakeSwarm, SwarmStateSize};
constexpr Kind kAttitudeKind = {kAttitude, MakeVehicle, VehicleStateSize};

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
