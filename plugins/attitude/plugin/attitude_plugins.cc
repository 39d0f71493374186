// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plugin family libmjf_attitude.so: thin adapters from the plugin ABI to the pure controllers
// PdCascade and Geometric (quadrotor) and PointMassDirect (double integrator).
#include <mjformation/plugin.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mjformation/plugin_contract.hpp>
#include <mjformation/plugin_util.hpp>
#include <string>

#include "mjformation/attitude/geometric.hpp"
#include "mjformation/attitude/pd_cascade.hpp"
#include "mjformation/attitude/pointmass_direct.hpp"

namespace {

using mjf::attitude::Geometric;
using mjf::attitude::Mixer;
using mjf::attitude::PdCascade;
using mjf::attitude::PointMassDirect;
using mjf::plugin::Attributes;
using mjf::plugin::ConfigError;
using mjf::plugin::Require;

mjf::attitude::VehicleState ToState(const mjfVehicleState& s) {
  mjf::attitude::VehicleState out;
  for (int i = 0; i < 3; ++i) {
    out.pos[i] = s.pos[i];
    out.vel[i] = s.vel[i];
    out.gyro[i] = s.gyro[i];
  }
  for (int i = 0; i < 4; ++i) out.quat[i] = s.quat[i];
  return out;
}

// The fields an attitude loop reads; false when one is not finite.
bool ToSetpoint(const mjfSetpoint& s, mjf::attitude::Setpoint* out) {
  for (int i = 0; i < 3; ++i) {
    out->acc[i] = s.acc[i];
    out->pos[i] = s.pos[i];
    out->vel[i] = s.vel[i];
  }
  out->yaw = s.yaw;
  return std::isfinite(s.acc[0]) && std::isfinite(s.acc[1]) && std::isfinite(s.acc[2]) &&
         std::isfinite(s.pos[2]) && std::isfinite(s.vel[2]) && std::isfinite(s.yaw);
}

const mjfVehicleInfo& RequireVehicle(const mjfCreateContext* ctx, int n_actuators) {
  if (!ctx->vehicle_info) throw ConfigError("no vehicle info: this is a per-vehicle plugin");
  if (ctx->vehicle < 0) throw ConfigError("no vehicle index: this is a per-vehicle plugin");
  if (ctx->vehicle_info->n_actuators != n_actuators || !ctx->vehicle_info->actuators) {
    throw ConfigError("expected " + std::to_string(n_actuators) + " actuators, got " +
                      std::to_string(ctx->vehicle_info->n_actuators));
  }
  return *ctx->vehicle_info;
}

std::array<mjf::attitude::RotorGeometry, Mixer::kRotors> ToRotors(const mjfVehicleInfo& info) {
  std::array<mjf::attitude::RotorGeometry, Mixer::kRotors> rotors;
  for (int k = 0; k < Mixer::kRotors; ++k) {
    const mjfActuatorInfo& a = info.actuators[k];
    for (int i = 0; i < 3; ++i) rotors[k].pos[i] = a.site_pos[i];
    for (int i = 0; i < 6; ++i) rotors[k].gear[i] = a.gear[i];
    rotors[k].ctrl_min = a.ctrl_min;
    rotors[k].ctrl_max = a.ctrl_max;
  }
  return rotors;
}

// ---------------------------------------------------------------------------------------------
// pd_cascade

constexpr const char* kTiltMax = mjf::plugin::contract::kTiltMax;
constexpr const char* kKpAtt = "kp_att";
constexpr const char* kKdAtt = "kd_att";
constexpr const char* kKpYaw = "kp_yaw";
constexpr const char* kKdYaw = "kd_yaw";
constexpr const char* kKpZ = "kp_z";
constexpr const char* kKiZ = "ki_z";
constexpr const char* kKdZ = "kd_z";
constexpr const char* kImaxZ = "imax_z";
constexpr const char* kDamping = "damping";
constexpr const char* kAllocation = "allocation";

// Defaults equal PdCascade::Gains{} (checked by tests/plugins/attitude/plugin_test.cc).
const mjfAttribute kCascadeAttributes[] = {
    {kTiltMax, "0",
     "rad: limit on the tilt (norm of roll, pitch references; 0: 0.35, lowered to torque "
     "authority / 3^2 rad/s^2 when that is smaller)"},
    {kKpAtt, "0",
     "1/s^2: roll/pitch proportional gain (angular acceleration per rad; 0: 150, lowered to the "
     "vehicle's torque authority)"},
    {kKdAtt, "0", "1/s: roll/pitch derivative gain on the body rate (0: 22, lowered with kp_att)"},
    {kKpYaw, "9", "1/s^2: yaw proportional gain"},
    {kKdYaw, "6", "1/s: yaw derivative gain on the body z rate"},
    {kKpZ, "6", "1/s^2: altitude proportional gain"},
    {kKiZ, "2", "1/s^3: altitude integral gain (0: none)"},
    {kKdZ, "5", "1/s: altitude derivative gain"},
    {kImaxZ, "2", "m/s^2: bound on the altitude integrator's acceleration (anti-windup)"},
    {kDamping, "body_rates",
     "roll/pitch damping on 'body_rates' (paper, near hover) or 'euler_rates' (large tilt)"},
    {kAllocation, "thrust_first",
     "mixer saturation priority: 'thrust_first' or 'roll_pitch_first' (large tilt)"},
};
const char* const kRotorNames[] = {"rotor0", "rotor1", "rotor2", "rotor3"};

// One instance per vehicle of a four-rotor controller (PdCascade, Geometric): both adapters
// check the step, convert the setpoint and state, and copy the rotor commands the same way.
template <typename Controller>
struct RotorInstance {
  int vehicle;
  Controller controller;
};

template <typename Controller>
int RotorCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<RotorInstance<Controller>*>(instance);
  if (self->vehicle >= ctx->n_vehicles || !ctx->controls) {
    return mjf::plugin::Fail(ctx,
                             "called for a vehicle the step does not have, or without controls");
  }
  mjf::attitude::Setpoint setpoint;
  if (!ToSetpoint(ctx->setpoints[self->vehicle], &setpoint)) {
    return mjf::plugin::Fail(ctx, "non-finite setpoint (acc, pos[2], vel[2] or yaw)", 2);
  }
  const typename Controller::Output out =
      self->controller.Update(ToState(ctx->states[self->vehicle]), setpoint, ctx->timestep);
  for (int k = 0; k < Mixer::kRotors; ++k) ctx->controls[k] = out.ctrl[k];
  return 0;
}

template <typename Controller>
void RotorReset(void* instance) {
  static_cast<RotorInstance<Controller>*>(instance)->controller.Reset();
}

template <typename Controller>
void RotorDestroy(void* instance) {
  delete static_cast<RotorInstance<Controller>*>(instance);
}

// Mass, gravity and principal inertia of the vehicle, for either controller's Vehicle.
template <typename Vehicle>
Vehicle RigidBody(const mjfVehicleInfo& info) {
  Vehicle vehicle;
  vehicle.mass = info.mass;
  vehicle.gravity = info.gravity;
  for (int i = 0; i < 3; ++i) vehicle.inertia[i] = info.inertia[i];
  return vehicle;
}

void* CascadeCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    PdCascade::Gains gains;
    gains.tilt_max = attributes.Number(kTiltMax);
    Require(gains.tilt_max >= 0 && gains.tilt_max < M_PI / 2, kTiltMax,
            "0 <= tilt_max < pi/2 (0: derived)", gains.tilt_max);
    const struct {
      const char* key;
      double* value;
      bool may_be_zero;
    } scalars[] = {{kKpAtt, &gains.kp_att, true},  {kKdAtt, &gains.kd_att, true},
                   {kKpYaw, &gains.kp_yaw, false}, {kKdYaw, &gains.kd_yaw, false},
                   {kKpZ, &gains.kp_z, false},     {kKiZ, &gains.ki_z, true},
                   {kKdZ, &gains.kd_z, false},     {kImaxZ, &gains.imax_z, true}};
    for (const auto& s : scalars) {
      *s.value = attributes.Number(s.key);
      Require(s.may_be_zero ? *s.value >= 0 : *s.value > 0, s.key, s.may_be_zero ? ">= 0" : "> 0",
              *s.value);
    }
    gains.euler_rate_damping =
        attributes.Choice(kDamping, {"body_rates", "euler_rates"}) == "euler_rates";
    gains.allocation =
        attributes.Choice(kAllocation, {"thrust_first", "roll_pitch_first"}) == "roll_pitch_first"
            ? Mixer::Priority::kRollPitchFirst
            : Mixer::Priority::kThrustFirst;
    const mjfVehicleInfo& info = RequireVehicle(ctx, Mixer::kRotors);
    return new RotorInstance<PdCascade>{
        ctx->vehicle, PdCascade(gains, RigidBody<PdCascade::Vehicle>(info), ToRotors(info))};
  });
}

// The attitude gains actually used (after the torque-authority derivation) and the loop's
// attitude gain kp / kd as `att_bw` with `tilt_max`: summary.json attitude_report, and the
// runner's torque-authority check compares att_bw^2 tilt_max with the vehicle's authority
// (docs/VEHICLES.md).
void CascadeReport(void* instance, mjfReportFn emit, void* user) {
  const PdCascade& c = static_cast<RotorInstance<PdCascade>*>(instance)->controller;
  const PdCascade::Gains& g = c.gains();
  emit(user, "kp_att", g.kp_att);
  emit(user, "kd_att", g.kd_att);
  emit(user, mjf::plugin::contract::kAttBw, g.kp_att / g.kd_att);
  emit(user, mjf::plugin::contract::kAttBwUnlimited, c.unlimited_att_bw());
  emit(user, kTiltMax, g.tilt_max);
}

const mjfPlugin kPdCascade = {
    MJF_ABI_VERSION,
    "pd_cascade",
    MJF_KIND_ATTITUDE,
    "quadrotor: model (9) -> roll/pitch refs, PD attitude, PID altitude, PD yaw, mixer",
    static_cast<int>(sizeof(kCascadeAttributes) / sizeof(kCascadeAttributes[0])),
    kCascadeAttributes,
    Mixer::kRotors,
    kRotorNames,
    CascadeCreate,
    RotorCompute<PdCascade>,
    RotorReset<PdCascade>,
    RotorDestroy<PdCascade>,
    CascadeReport};

// ---------------------------------------------------------------------------------------------
// geometric

constexpr const char* kRateBw = "rate_bw";
constexpr const char* kAttBw = mjf::plugin::contract::kAttBw;
constexpr const char* kYawBw = "yaw_bw";
constexpr const char* kZBw = "z_bw";
constexpr const char* kRateKi = "rate_ki";
constexpr const char* kThrustMargin = "thrust_margin";

// Defaults equal Geometric::Gains{} (checked by tests/plugins/attitude/plugin_test.cc); 0 = derived
// from the vehicle info (motor lag, inertia, mass, rotor limits).
const mjfAttribute kGeometricAttributes[] = {
    {kTiltMax, "0",
     "rad: limit on the angle of the thrust vector from the vertical (0: 0.78, lowered to torque "
     "authority / 3^2 rad/s^2 when that is smaller)"},
    {kRateBw, "0",
     "rad/s: body-rate loop crossover (0: 0.9 / (motor lag + 2 timesteps), at most 4 sqrt(torque "
     "authority / tilt_max))"},
    {kAttBw, "0", "rad/s: roll/pitch attitude loop bandwidth (0: rate_bw / 4)"},
    {kYawBw, "0", "rad/s: yaw attitude loop bandwidth (0: att_bw / 2)"},
    {kZBw, "0", "rad/s: altitude loop natural frequency (0: att_bw / 2.5)"},
    {kRateKi, "0.1", "rate integral zero as a fraction of rate_bw (0: no integral, <= 0.5)"},
    {kThrustMargin, "0.1", "fraction of the rotors' total thrust kept for torque (0 .. 0.5)"},
};

void* GeometricCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    Geometric::Gains gains;
    gains.tilt_max = attributes.Number(kTiltMax);
    Require(gains.tilt_max >= 0 && gains.tilt_max < M_PI / 2, kTiltMax,
            "0 <= tilt_max < pi/2 (0: derived)", gains.tilt_max);
    const struct {
      const char* key;
      double* value;
    } bandwidths[] = {{kRateBw, &gains.rate_bw},
                      {kAttBw, &gains.att_bw},
                      {kYawBw, &gains.yaw_bw},
                      {kZBw, &gains.z_bw}};
    for (const auto& b : bandwidths) {
      *b.value = attributes.Number(b.key);
      Require(*b.value >= 0, b.key, ">= 0 (0: derived from the vehicle)", *b.value);
    }
    gains.rate_ki = attributes.Number(kRateKi);
    Require(gains.rate_ki >= 0 && gains.rate_ki <= 0.5, kRateKi, "0 <= rate_ki <= 0.5",
            gains.rate_ki);
    gains.thrust_margin = attributes.Number(kThrustMargin);
    Require(gains.thrust_margin >= 0 && gains.thrust_margin < 0.5, kThrustMargin,
            "0 <= thrust_margin < 0.5", gains.thrust_margin);
    const mjfVehicleInfo& info = RequireVehicle(ctx, Mixer::kRotors);
    Geometric::Vehicle vehicle = RigidBody<Geometric::Vehicle>(info);
    for (int k = 0; k < Mixer::kRotors; ++k) {
      vehicle.motor_lag = std::max(vehicle.motor_lag, info.actuators[k].time_constant);
    }
    vehicle.timestep = ctx->timestep;
    // Geometric's own checks (derived bandwidths, hover authority) throw invalid_argument
    // naming the key; CreateOrExplain passes the message on.
    return new RotorInstance<Geometric>{ctx->vehicle, Geometric(gains, vehicle, ToRotors(info))};
  });
}

// The bandwidths actually used (rad/s), after the derivation from the vehicle and the torque cap
// (summary.json attitude_report), so that a run on a small vehicle shows what it flew with; with
// tilt_max, what the runner's torque-authority check reads (docs/VEHICLES.md).
void GeometricReport(void* instance, mjfReportFn emit, void* user) {
  const Geometric& c = static_cast<RotorInstance<Geometric>*>(instance)->controller;
  const Geometric::Gains& g = c.gains();
  emit(user, "rate_bw", g.rate_bw);
  emit(user, kAttBw, g.att_bw);
  emit(user, mjf::plugin::contract::kAttBwUnlimited, c.unlimited_att_bw());
  emit(user, "yaw_bw", g.yaw_bw);
  emit(user, "z_bw", g.z_bw);
  emit(user, kTiltMax, g.tilt_max);
}

const mjfPlugin kGeometric = {
    MJF_ABI_VERSION,
    "geometric",
    MJF_KIND_ATTITUDE,
    "quadrotor: acceleration -> thrust vector (nonlinear, tilt limit with altitude priority) -> "
    "quaternion attitude -> body-rate PI -> mixer keeping roll/pitch; gains from the vehicle",
    static_cast<int>(sizeof(kGeometricAttributes) / sizeof(kGeometricAttributes[0])),
    kGeometricAttributes,
    Mixer::kRotors,
    kRotorNames,
    GeometricCreate,
    RotorCompute<Geometric>,
    RotorReset<Geometric>,
    RotorDestroy<Geometric>,
    GeometricReport};

// ---------------------------------------------------------------------------------------------
// pointmass_direct

const mjfAttribute kPointMassAttributes[] = {
    {kKpZ, "6", "1/s^2: altitude proportional gain"},
    {kKdZ, "5", "1/s: altitude derivative gain"},
};
const char* const kForceNames[] = {"fx", "fy", "fz"};

struct PointMassInstance {
  int vehicle;
  PointMassDirect controller;
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
    return new PointMassInstance{ctx->vehicle, PointMassDirect(gains, info.mass, info.gravity)};
  });
}

int PointMassCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<PointMassInstance*>(instance);
  if (self->vehicle >= ctx->n_vehicles || !ctx->controls) {
    return mjf::plugin::Fail(ctx,
                             "called for a vehicle the step does not have, or without controls");
  }
  mjf::attitude::Setpoint setpoint;
  if (!ToSetpoint(ctx->setpoints[self->vehicle], &setpoint)) {
    return mjf::plugin::Fail(ctx, "the setpoint is not finite", 2);
  }
  const auto force = self->controller.Update(ToState(ctx->states[self->vehicle]), setpoint);
  for (int k = 0; k < 3; ++k) ctx->controls[k] = force[k];
  return 0;
}

void PointMassReset(void*) {}
void PointMassDestroy(void* instance) { delete static_cast<PointMassInstance*>(instance); }

const mjfPlugin kPointMassDirect = {
    MJF_ABI_VERSION,
    "pointmass_direct",
    MJF_KIND_ATTITUDE,
    "double integrator: force = m * acceleration command, PD altitude, gravity compensated",
    static_cast<int>(sizeof(kPointMassAttributes) / sizeof(kPointMassAttributes[0])),
    kPointMassAttributes,
    3,
    kForceNames,
    PointMassCreate,
    PointMassCompute,
    PointMassReset,
    PointMassDestroy,
    nullptr};

}  // namespace

MJF_EXPORT_PLUGINS(&kPdCascade, &kGeometric, &kPointMassDirect)
