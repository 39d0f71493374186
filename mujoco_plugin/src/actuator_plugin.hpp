// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The MuJoCo callbacks (mjpPlugin) that mjformation's native plugins share: both are actuator
// plugins over a bridge to our own plugin ABI, with the same timing, state and actuation,
// described here. The plugin-specific part (how an instance's bridge is made, its state's size)
// is a PluginKind: swarm_plugin.hpp (mjformation.swarm), attitude_plugin.hpp
// (mjformation.attitude). Both declare the passive capability too, so that a body may reference
// an instance (MuJoCo's attach keeps only the instances an attached element references, and the
// bodies referencing an instance tell the names an attach gave its vehicles, attach_names.hpp),
// and so that the swarm knows when qfrc_passive is recomputed (see Compute: its forces besides
// the actuators).
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
//   runner::ControlTick::GetState, ABI 4, then the force stages'). Layout 3; layout 2 stored the
//   plugin ABI's vehicle states and estimates as 32-bit halves (fixed_state_archive.hpp), and
//   layout 1 had neither the mark nor the held forces.
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
#ifndef MJFORMATION_MUJOCO_PLUGIN_ACTUATOR_PLUGIN_HPP_
#define MJFORMATION_MUJOCO_PLUGIN_ACTUATOR_PLUGIN_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <vector>

#include "native_instance.hpp"

namespace mjf::native {

// What makes one native plugin itself: its name, how an instance's holder is built from the
// model's configuration (throws std::runtime_error naming the instance), and its tick state's
// size while the model compiles.
struct PluginKind {
  const char* name;
  std::unique_ptr<Holder> (*make)(const mjModel* m, int instance);
  size_t (*state_size)(const mjModel* m, int instance);
};

// The callbacks of the plugin K, in the order MuJoCo calls them.
template <const PluginKind& K>
class ActuatorPlugin {
 public:
  // Registers K with MuJoCo under K.name with these <config> attributes, unless a plugin of
  // that name is registered already (another copy of this library, loaded first, flies).
  static void Register(const std::vector<const char*>& attributes);

  // nstate, while the model compiles: the header, one held control per actuator and the tick's
  // state. Refuses (as the compile error) a vehicle driven twice and a configuration that does
  // not read.
  static int NState(const mjModel* m, int instance);
  // init (mj_makeData): builds d's holder, or warns naming the instance and returns -1 (MuJoCo
  // then refuses the mjData); clears the state header.
  static int Init(const mjModel* m, mjData* d, int instance);
  // destroy (mj_deleteData): frees d's own holder, never one whose pointer a raw copy brought.
  static void Destroy(mjData* d, int instance);
  // copy (mj_copyData, mjv_copyData): the state came with plugin_state; dest keeps the holder it
  // had (a viewer copying every frame into one mjData builds nothing) or gets one at its tick.
  static void Copy(mjData* dest, const mjModel* m, const mjData* src, int instance);
  // reset (mj_resetData): clears plugin_state's header; the next tick starts from the holder's
  // initial state. Nothing is rebuilt, no file is read.
  static void Reset(const mjModel* m, mjtNum* plugin_state, void* plugin_data, int instance);
  // actuator_act_dot (after MuJoCo's own act_dot): act_dot of the driven filter actuators from
  // the held controls, the step's tick run first if it has not run.
  static void ActDot(const mjModel* m, mjData* d, int instance);
  // compute. The passive capability's call (mj_passive has just cleared and summed
  // qfrc_passive) marks qfrc_passive recomputed. The actuator capability's (mj_fwdActuation,
  // after MuJoCo's own forces): actuator_force of the driven actuators without activation, then
  // the held forces besides the actuators' ([wind], the wrench rotor model) into qfrc_passive,
  // once per mark. Forces go into qfrc_passive, not qfrc_applied (the user's input, and part of
  // the state): MuJoCo sums qfrc_smooth = passive - bias + applied + actuator, and with no spring
  // or damper passive is +0 where the runner's qfrc_applied was, so the sums are the runner's
  // bits (the runner adds them into qfrc_passive too, after mj_step1). An evaluation that skips
  // the velocity stage (mjd_transitionFD's control and activation columns, mj_forwardSkip) keeps
  // the qfrc_passive of the evaluation before it, forces included: without the mark they would
  // be added twice.
  static void Compute(const mjModel* m, mjData* d, int instance, int capability);
  // advance (after the step's integration): commits the step whose tick ran, and the wrench
  // rotor model's motor lags follow its controls (the runner's Actuation::Advance after
  // mj_step2).
  static void Advance(const mjModel* m, mjData* d, int instance);

 private:
  // d's holder: its own, or one built for it (a copy, an unpickled MjData, a failed build
  // before).
  static Holder* HolderFor(const mjModel* m, mjData* d, int instance);
  // The held controls of the current step, the tick run once for it (the tick rule above).
  static mjtNum* HeldControls(const mjModel* m, mjData* d, int instance);
  // The step's forces besides the actuators' into qfrc_passive, once per mark (Compute).
  static void AddHeldForces(const mjModel* m, mjData* d, int instance);
};

}  // namespace mjf::native

#endif  // MJFORMATION_MUJOCO_PLUGIN_ACTUATOR_PLUGIN_HPP_
