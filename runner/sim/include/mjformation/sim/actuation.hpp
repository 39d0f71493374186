// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// How the attitude plugins' controls reach MuJoCo, chosen once per simulation
// ([vehicles] rotor_model): MuJoCo's own actuators (d->ctrl), or the runner's wrench model
// (each rotor's thrust and yaw torque as a generalized force over the vehicle's own dofs).
#ifndef MJFORMATION_SIM_ACTUATION_HPP_
#define MJFORMATION_SIM_ACTUATION_HPP_

#include <mujoco/mujoco.h>

#include <memory>
#include <vector>

#include "mjformation/config/experiment.hpp"
#include "mjformation/config/fixed_state_archive.hpp"
#include "mjformation/config/state_archive.hpp"
#include "mjformation/scene/vehicle_binding.hpp"

namespace mjf::runner {

class Actuation {
 public:
  virtual ~Actuation() = default;
  // Hands every vehicle's controls ([vehicle][actuator]) to MuJoCo, after mj_step1 and before
  // mj_step2: into d->ctrl, or (the wrench model) added into qfrc_passive, which mj_step1 has
  // just computed (AddWrenchAtCentreOfMass).
  virtual void Apply(const std::vector<double>& controls, mjData* data) = 0;
  // After mj_step2: advances the actuation's own state (the wrench model's motor lag).
  virtual void Advance(const std::vector<double>& controls) = 0;
  // What Advance carries from one step to the next (the wrench model's motor lags), both ways
  // (checkpoints, state_archive.hpp; the native plugin's plugin_state, fixed_state_archive.hpp);
  // nothing for the actuators MuJoCo integrates itself.
  virtual void VisitState(StateArchive& archive) { (void)archive; }
  virtual void VisitState(FixedStateArchive& archive) { (void)archive; }
};

// The actuation model the experiment asks for.
std::unique_ptr<Actuation> MakeActuation(RotorModel model, const mjModel* m,
                                         const VehicleBindings& bindings, double timestep);

// `inner` with the experiment's rotor faults ([[vehicles.fault]]) on the vehicles `bindings`
// holds (vehicle `first_vehicle` and on; 0 = leader): from a fault's time on, the rotor's control
// becomes (1 - thrust_share) x its control clamped to the actuator's range, before either rotor
// model sees it (thrust is linear in the control in both, so the rotor gives that share less
// thrust, and its yaw torque with it). Returns `inner` itself when no fault is on these vehicles.
// Throws ConfigError naming the fault's line for a rotor the vehicle does not have.
std::unique_ptr<Actuation> WithRotorFaults(std::unique_ptr<Actuation> inner,
                                           const ExperimentConfig& config,
                                           const VehicleBindings& bindings, int first_vehicle);

// Adds J^T [force; torque] of a wrench acting at `body`'s centre of mass (world frame) to
// qfrc_passive, over the dofs that move the body only (O(dofs of the body's chain)). Called
// after the velocity stage (mj_step1; an engine plugin's actuation stage), which computes
// qfrc_passive: MuJoCo then sums qfrc_smooth = passive - bias + applied + actuator. Not
// qfrc_applied, which is the user's input and part of MuJoCo's state (mj_getState), so that
// the native plugin can add the same forces; with no spring or damper qfrc_passive is +0 where
// qfrc_applied was, and the sums are the same bits.
void AddWrenchAtCentreOfMass(const mjModel* m, mjData* d, int body, const mjtNum wrench[6]);

}  // namespace mjf::runner

#endif  // MJFORMATION_SIM_ACTUATION_HPP_
