// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "actuator_plugin.hpp"

#include <mujoco/mjplugin.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>

#include "attitude_plugin.hpp"
#include "one_driver.hpp"
#include "swarm_plugin.hpp"

namespace mjf::native {
namespace {

// plugin_state's header (actuator_plugin.hpp).
constexpr int kLayout = 0, kCommitted = 1, kHeld = 2, kValid = 3, kPassive = 4, kHeader = 5;
constexpr double kLayoutVersion = 3;

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

}  // namespace

// Called while the model compiles: a refusal becomes the compile error.
template <const PluginKind& K>
int ActuatorPlugin<K>::NState(const mjModel* m, int instance) {
  size_t blocks = 0;
  ErrorFromException([&] {
    RefuseDrivingTwice(K.name, m, instance);
    blocks = K.state_size(m, instance);
  });
  return kHeader + static_cast<int>(m->nactuator + blocks);
}

// d's holder: its own, or one built for it (a copy, an unpickled MjData, a failed build
// before). Never a pointer that plugin_data holds but the table does not give to d.
template <const PluginKind& K>
Holder* ActuatorPlugin<K>::HolderFor(const mjModel* m, mjData* d, int instance) {
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

template <const PluginKind& K>
int ActuatorPlugin<K>::Init(const mjModel* m, mjData* d, int instance) {
  try {
    HolderFor(m, d, instance);
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

template <const PluginKind& K>
void ActuatorPlugin<K>::Destroy(mjData* d, int instance) {
  Holders::Get().Release(d, instance);  // frees it; a raw copy of another's pointer is not ours
  d->plugin_data[instance] = 0;
}

// A reset only clears plugin_state: the next tick starts from the holder's initial state.
// Nothing is rebuilt, no file is read.
template <const PluginKind& K>
void ActuatorPlugin<K>::Reset(const mjModel* m, mjtNum* plugin_state, void*, int instance) {
  ClearState(m, instance, plugin_state);
}

// The tick of the current step, once (see the file comment).
template <const PluginKind& K>
mjtNum* ActuatorPlugin<K>::HeldControls(const mjModel* m, mjData* d, int instance) {
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
    Holder* holder = HolderFor(m, d, instance);
    mjtNum* held = controls + m->nactuator;
    mjtNum* blocks = held + holder->held_size();
    const bool from_blocks = state[kValid] != 0;
    holder->SetState(from_blocks ? blocks : holder->initial.data());
    const auto step = static_cast<int64_t>(state[kCommitted]);
    holder->Tick(step, m, d, controls, held);
    // Loaded from the blocks, they hold the state before the tick: only what changed is written.
    if (from_blocks) {
      holder->UpdateState(blocks);
    } else {
      holder->GetState(blocks);
    }
    state[kValid] = 1;
    state[kHeld] = state[kCommitted];
  });
  return controls;
}

template <const PluginKind& K>
void ActuatorPlugin<K>::ActDot(const mjModel* m, mjData* d, int instance) {
  const mjtNum* u = HeldControls(m, d, instance);
  const bool bad = ControlsBad(m, d);
  for (int a = 0; a < m->nactuator; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] == 0) continue;
    const int adr = m->actuator_actadr[a] + m->actuator_actnum[a] - 1;
    const mjtNum tau = mju_max(mjMINVAL, m->actuator_dynprm[mjNDYN * a]);
    d->act_dot[adr] = (Applied(m, d, bad, a, u[a]) - d->act[adr]) / tau;
  }
}

template <const PluginKind& K>
void ActuatorPlugin<K>::Compute(const mjModel* m, mjData* d, int instance, int capability) {
  if (capability == mjPLUGIN_PASSIVE) {
    State(m, d, instance)[kPassive] = 1;
    return;
  }
  if (capability != mjPLUGIN_ACTUATOR) return;
  const mjtNum* u = HeldControls(m, d, instance);
  const bool bad = ControlsBad(m, d);
  for (int a = 0; a < m->nactuator; ++a) {
    if (std::isnan(u[a]) || m->actuator_actnum[a] != 0) continue;
    mjtNum force = m->actuator_gainprm[mjNGAIN * a] * Applied(m, d, bad, a, u[a]);
    // Not dead: MuJoCo computes gain * ctrl + bias, and the (zero) bias of a biastype="none"
    // actuator turns a -0.0 force into +0.0. The same bits as the runner's need the same sum.
    force += 0.0;
    d->actuator_force[m->actuator_outadr[a]] = force;
  }
  AddHeldForces(m, d, instance);
}

template <const PluginKind& K>
void ActuatorPlugin<K>::AddHeldForces(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  if (state[kPassive] == 0) {
    // With springs and dampers both disabled MuJoCo skips mj_passive and its plugins: the
    // forces would never be added, and the scene would fly on without its wind or rotors.
    const int both = mjDSBL_SPRING | mjDSBL_DAMPER;
    if ((m->opt.disableflags & both) == both) {
      ErrorFromException([&] {
        if (HolderFor(m, d, instance)->held_size() == 0) return;
        throw std::runtime_error(
            InstanceWhere(K.name, m, instance) +
            ": springs and dampers are both disabled (<flag spring=\"disable\" "
            "damper=\"disable\"/>, m.opt.disableflags), so MuJoCo skips the passive stage "
            "where this scene's forces besides the actuators ([wind], the wrench rotor model) "
            "are added; enable either");
      });
    }
    return;
  }
  state[kPassive] = 0;
  ErrorFromException([&] {
    Holder* holder = HolderFor(m, d, instance);
    if (holder->held_size()) holder->AddForces(m, d, state + kHeader + m->nactuator);
  });
}

template <const PluginKind& K>
void ActuatorPlugin<K>::Advance(const mjModel* m, mjData* d, int instance) {
  mjtNum* state = State(m, d, instance);
  if (state[kHeld] == state[kCommitted]) {
    ErrorFromException([&] {
      Holder* holder = HolderFor(m, d, instance);
      if (holder->held_size()) holder->Advance(m, state + kHeader + m->nactuator);
    });
  }
  state[kCommitted] += 1;
}

// The copy's state came with plugin_state; dest keeps the holder it had (a viewer copying
// every frame into one mjData builds nothing) or gets one at its first tick.
template <const PluginKind& K>
void ActuatorPlugin<K>::Copy(mjData* dest, const mjModel*, const mjData*, int instance) {
  Holder* own = Holders::Get().Find(dest, instance);
  dest->plugin_data[instance] = reinterpret_cast<uintptr_t>(own);
}

template <const PluginKind& K>
void ActuatorPlugin<K>::Register(const std::vector<const char*>& attributes) {
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

// The two plugins (swarm_plugin.cc and attitude_plugin.cc register them).
template class ActuatorPlugin<kSwarmKind>;
template class ActuatorPlugin<kAttitudeKind>;

}  // namespace mjf::native
