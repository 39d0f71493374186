// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What the attitude adapters share: the attribute keys several controllers read, the conversions
// from the ABI's state, setpoint and vehicle info to the controllers' types, and the one
// instance, compute, reset and destroy every per-vehicle attitude controller uses. Each adapter
// writes ctx->controls (its actuators, in the order of its actuator names).
#ifndef MJFORMATION_ATTITUDE_PLUGIN_ADAPTER_HPP_
#define MJFORMATION_ATTITUDE_PLUGIN_ADAPTER_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <cstddef>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>

#include "mjformation/attitude/mixer.hpp"
#include "mjformation/attitude/types.hpp"

namespace mjf::attitude::adapter {

// Attribute keys several controllers declare.
constexpr const char* kTiltMax = plugin::contract::kTiltMax;  // the runner reads it
constexpr const char* kKpZ = "kp_z";
constexpr const char* kKdZ = "kd_z";

// The four rotors' actuator names (pd_cascade, geometric).
extern const char* const kRotorNames[Mixer::kRotors];

VehicleState ToState(const mjfVehicleState& s);
// The fields an attitude loop reads; false when one is not finite.
bool ToSetpoint(const mjfSetpoint& s, Setpoint* out);
// The vehicle info of a per-vehicle plugin with n_actuators actuators; ConfigError otherwise.
const mjfVehicleInfo& RequireVehicle(const mjfCreateContext* ctx, int n_actuators);
std::array<RotorGeometry, Mixer::kRotors> ToRotors(const mjfVehicleInfo& info);
// The tilt limit of a quadrotor controller, rad: 0 <= tilt_max < pi/2 (0: derived from the
// vehicle); ConfigError naming the key otherwise.
double ReadTiltMax(const mjf::plugin::Attributes& attributes);

// Mass, gravity and principal inertia of the vehicle, for either rotor controller's Vehicle.
template <typename Vehicle>
Vehicle RigidBody(const mjfVehicleInfo& info) {
  Vehicle vehicle;
  vehicle.mass = info.mass;
  vehicle.gravity = info.gravity;
  for (int i = 0; i < 3; ++i) vehicle.inertia[i] = info.inertia[i];
  return vehicle;
}

// One instance per vehicle of an attitude controller.
template <typename Controller>
struct VehicleInstance {
  int vehicle;
  Controller controller;
  template <typename Visit>
  void VisitState(Visit& visit) {
    controller.VisitState(visit);
  }
};

// How compute() drives a four-rotor controller (PdCascade, Geometric): Update(state, setpoint,
// dt) gives four rotor commands. A controller of another shape has a Drive of its own with the
// same members.
template <typename RotorController>
struct RotorDrive {
  using Controller = RotorController;
  static constexpr char kNonFiniteSetpoint[] = "non-finite setpoint (acc, pos[2], vel[2] or yaw)";
  static void Command(Controller& controller, const VehicleState& state, const Setpoint& setpoint,
                      double timestep, double* controls) {
    const typename Controller::Output out = controller.Update(state, setpoint, timestep);
    for (int k = 0; k < Mixer::kRotors; ++k) controls[k] = out.ctrl[k];
  }
  static void Reset(Controller& controller) { controller.Reset(); }
};

// Checks the step, converts the setpoint and state, and lets Drive write the controls.
template <typename Drive>
int AttitudeCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<VehicleInstance<typename Drive::Controller>*>(instance);
  if (self->vehicle >= ctx->n_vehicles || !ctx->controls) {
    return mjf::plugin::Fail(ctx,
                             "called for a vehicle the step does not have, or without controls");
  }
  Setpoint setpoint;
  if (!ToSetpoint(ctx->setpoints[self->vehicle], &setpoint)) {
    return mjf::plugin::Fail(ctx, Drive::kNonFiniteSetpoint, 2);
  }
  Drive::Command(self->controller, ToState(ctx->states[self->vehicle]), setpoint, ctx->timestep,
                 ctx->controls);
  return 0;
}

template <typename Drive>
void AttitudeReset(void* instance) {
  Drive::Reset(static_cast<VehicleInstance<typename Drive::Controller>*>(instance)->controller);
}

template <typename Drive>
void AttitudeDestroy(void* instance) {
  delete static_cast<VehicleInstance<typename Drive::Controller>*>(instance);
}

// The descriptor of an attitude plugin whose instance is VehicleInstance<Drive::Controller>.
template <typename Drive, size_t kAttributes, size_t kActuators>
constexpr mjfPlugin AttitudePlugin(const char* name, const char* doc,
                                   const mjfAttribute (&attributes)[kAttributes],
                                   const char* const (&actuator_names)[kActuators],
                                   void* (*create)(const mjfCreateContext*),
                                   void (*report)(void*, mjfReportFn, void*) = nullptr) {
  using Instance = VehicleInstance<typename Drive::Controller>;
  static_assert(mjf::plugin::kHasVisitState<typename Drive::Controller>,
                "an attitude controller lists its state: template <typename Visit> void "
                "VisitState(Visit&) (mjformation/plugin_state.hpp)");
  return {MJF_ABI_VERSION,
          name,
          MJF_KIND_ATTITUDE,
          doc,
          static_cast<int>(kAttributes),
          attributes,
          static_cast<int>(kActuators),
          actuator_names,
          create,
          AttitudeCompute<Drive>,
          AttitudeReset<Drive>,
          AttitudeDestroy<Drive>,
          report,
          &mjf::plugin::StateSizeOf<Instance>,
          &mjf::plugin::GetStateOf<Instance>,
          &mjf::plugin::SetStateOf<Instance>};
}

// The descriptors, one per file (register.cc lists them).
extern const mjfPlugin kPdCascade;        // pd_cascade.cc
extern const mjfPlugin kGeometric;        // geometric.cc
extern const mjfPlugin kPointMassDirect;  // pointmass_direct.cc

}  // namespace mjf::attitude::adapter

#endif  // MJFORMATION_ATTITUDE_PLUGIN_ADAPTER_HPP_
