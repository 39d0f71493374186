// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// pointmass_direct: the adapter of PointMassDirect (a double integrator driven by a force).
#include "mjformation/attitude/pointmass_direct.hpp"

#include "adapter.hpp"

namespace mjf::attitude::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::Require;

const mjfAttribute kPointMassAttributes[] = {
    {kKpZ, "6", "1/s^2: altitude proportional gain"},
    {kKdZ, "5", "1/s: altitude derivative gain"},
};
const char* const kForceNames[] = {"fx", "fy", "fz"};

// How compute() drives PointMassDirect: a world force per axis, no timestep, no state to reset.
struct PointMassDrive {
  using Controller = PointMassDirect;
  static constexpr char kNonFiniteSetpoint[] = "the setpoint is not finite";
  static void Command(const Controller& controller, const VehicleState& state,
                      const Setpoint& setpoint, double /*timestep*/, double* controls) {
    const auto force = controller.Update(state, setpoint);
    for (int k = 0; k < 3; ++k) controls[k] = force[k];
  }
  static void Reset(Controller&) {}
};

void* PointMassCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    PointMassDirect::Gains gains;
    gains.kp_z = attributes.Number(kKpZ);
    Require(gains.kp_z >= 0, kKpZ, ">= 0", gains.kp_z);
    gains.kd_z = attributes.Number(kKdZ);
    Require(gains.kd_z >= 0, kKdZ, ">= 0", gains.kd_z);
    const mjfVehicleInfo& info = RequireVehicle(ctx, 3);
    return new VehicleInstance<PointMassDirect>{ctx->vehicle,
                                                PointMassDirect(gains, info.mass, info.gravity)};
  });
}

}  // namespace

const mjfPlugin kPointMassDirect = AttitudePlugin<PointMassDrive>(
    "pointmass_direct",
    "double integrator: force = m * acceleration command, PD altitude, gravity compensated",
    kPointMassAttributes, kForceNames, PointMassCreate);

}  // namespace mjf::attitude::adapter
