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
    return new LeaderInstance<CircleGuidance>{CheckVehicle(ctx), CircleGuidance(config)};
  });
}

}  // namespace

const mjfPlugin kCircle = LeaderPlugin<CircleGuidance>(
    "circle",
    "leader circle: a = a_ref + kp (p_ref - p) + kd (v_ref - v), constant altitude and yaw",
    kCircleAttributes, CircleCreate);

}  // namespace mjf::guidance::adapter
