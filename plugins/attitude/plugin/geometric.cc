// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// geometric: the adapter of Geometric (thrust vector, quaternion attitude, body-rate PI), its
// gains derived from the vehicle info when left at 0.
#include "mjformation/attitude/geometric.hpp"

#include <algorithm>

#include "adapter.hpp"

namespace mjf::attitude::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::Require;

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
    gains.tilt_max = ReadTiltMax(attributes);
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
    return new VehicleInstance<Geometric>{ctx->vehicle, Geometric(gains, vehicle, ToRotors(info))};
  });
}

// The bandwidths actually used (rad/s), after the derivation from the vehicle and the torque cap
// (summary.json attitude_report), so that a run on a small vehicle shows what it flew with; with
// tilt_max, what the runner's torque-authority check reads (docs/VEHICLES.md).
void GeometricReport(void* instance, mjfReportFn emit, void* user) {
  const Geometric& c = static_cast<VehicleInstance<Geometric>*>(instance)->controller;
  const Geometric::Gains& g = c.gains();
  emit(user, "rate_bw", g.rate_bw);
  emit(user, kAttBw, g.att_bw);
  emit(user, mjf::plugin::contract::kAttBwUnlimited, c.unlimited_att_bw());
  emit(user, "yaw_bw", g.yaw_bw);
  emit(user, "z_bw", g.z_bw);
  emit(user, kTiltMax, g.tilt_max);
}

}  // namespace

const mjfPlugin kGeometric = AttitudePlugin<RotorDrive<Geometric>>(
    "geometric",
    "quadrotor: acceleration -> thrust vector (nonlinear, tilt limit with altitude priority) -> "
    "quaternion attitude -> body-rate PI -> mixer keeping roll/pitch; gains from the vehicle",
    kGeometricAttributes, kRotorNames, GeometricCreate, GeometricReport);

}  // namespace mjf::attitude::adapter
