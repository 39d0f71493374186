// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// circle: the adapter of CircleGuidance (the paper's leader).
#include "mjformation/guidance/circle.hpp"

#include <string>

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::Require;

const mjfAttribute kCircleAttributes[] = {
    {kRadius, "20", "m: circle radius (paper: 20)"},
    {kOmega, "0.157", "rad/s: angular rate, > 0 counter-clockwise (paper: 0.157)"},
    {kCenter, "0 0", "m: circle centre x y"},
    {kPhase, "0", "rad: angle at t = 0 (0: start at centre + (radius, 0))"},
    rows::kAltitude,
    rows::kYaw,
    rows::kKp,
    rows::kKd,
};

struct CircleInstance {
  int vehicle;
  CircleGuidance guidance;
};

void* CircleCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    CircleGuidance::Config config;
    config.radius = attributes.Number(kRadius);
    Require(config.radius >= 0, kRadius, ">= 0", config.radius);
    config.omega = attributes.Number(kOmega);
    const auto center = attributes.Numbers(kCenter, 2);
    config.center = {center[0], center[1]};
    config.phase = attributes.Number(kPhase);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new CircleInstance{CheckVehicle(ctx), CircleGuidance(config)};
  });
}

int CircleCompute(void* instance, const mjfStepContext* ctx) {
  auto* self = static_cast<CircleInstance*>(instance);
  if (self->vehicle >= ctx->n_vehicles) {
    return mjf::plugin::Fail(ctx, "called for a vehicle the step does not have");
  }
  const mjfVehicleState& s = ctx->states[self->vehicle];
  Write(self->guidance.Update(ctx->time, Get(s.pos), Get(s.vel)), &ctx->setpoints[self->vehicle]);
  return 0;
}

void CircleDestroy(void* instance) { delete static_cast<CircleInstance*>(instance); }

}  // namespace

const mjfPlugin kCircle = {
    MJF_ABI_VERSION,
    "circle",
    MJF_KIND_GUIDANCE,
    "leader circle: a = a_ref + kp (p_ref - p) + kd (v_ref - v), constant altitude and yaw",
    static_cast<int>(sizeof(kCircleAttributes) / sizeof(kCircleAttributes[0])),
    kCircleAttributes,
    0,
    nullptr,
    CircleCreate,
    CircleCompute,
    nullptr,
    CircleDestroy,
    nullptr};

}  // namespace mjf::guidance::adapter
