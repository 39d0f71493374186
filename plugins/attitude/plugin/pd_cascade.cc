// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// pd_cascade: the adapter of PdCascade (the paper's quadrotor loop, model (9)).
#include "mjformation/attitude/pd_cascade.hpp"

#include "adapter.hpp"

namespace mjf::attitude::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::Require;

constexpr const char* kKpAtt = "kp_att";
constexpr const char* kKdAtt = "kd_att";
constexpr const char* kKpYaw = "kp_yaw";
constexpr const char* kKdYaw = "kd_yaw";
constexpr const char* kKiZ = "ki_z";
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

void* CascadeCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    PdCascade::Gains gains;
    gains.tilt_max = ReadTiltMax(attributes);
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
    return new VehicleInstance<PdCascade>{
        ctx->vehicle, PdCascade(gains, RigidBody<PdCascade::Vehicle>(info), ToRotors(info))};
  });
}

// The attitude gains actually used (after the torque-authority derivation) and the loop's
// attitude gain kp / kd as `att_bw` with `tilt_max`: summary.json attitude_report, and the
// runner's torque-authority check compares att_bw^2 tilt_max with the vehicle's authority
// (docs/VEHICLES.md).
void CascadeReport(void* instance, mjfReportFn emit, void* user) {
  const PdCascade& c = static_cast<VehicleInstance<PdCascade>*>(instance)->controller;
  const PdCascade::Gains& g = c.gains();
  emit(user, "kp_att", g.kp_att);
  emit(user, "kd_att", g.kd_att);
  emit(user, mjf::plugin::contract::kAttBw, g.kp_att / g.kd_att);
  emit(user, mjf::plugin::contract::kAttBwUnlimited, c.unlimited_att_bw());
  emit(user, kTiltMax, g.tilt_max);
}

}  // namespace

const mjfPlugin kPdCascade = AttitudePlugin<RotorDrive<PdCascade>>(
    "pd_cascade",
    "quadrotor: model (9) -> roll/pitch refs, PD attitude, PID altitude, PD yaw, mixer",
    kCascadeAttributes, kRotorNames, CascadeCreate, CascadeReport);

}  // namespace mjf::attitude::adapter
