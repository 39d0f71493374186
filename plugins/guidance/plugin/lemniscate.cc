// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// lemniscate: the adapter of LemniscateGuidance.
#include "mjformation/guidance/lemniscate.hpp"

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

constexpr const char* kHalfWidth = "half_width";
const mjfAttribute kLemniscateAttributes[] = {
    rows::kAMin,
    rows::kAMax,
    {kHalfWidth, "20", "m: A, x = cx + A sin(w t + phase), y = cy + A/2 sin(2 (w t + phase))"},
    {kOmega, "0.15", "rad/s: w (peak accelerations A w^2 on x, 2 A w^2 on y)"},
    {kCenter, "0 0", "m: centre x y"},
    {kPhase, "0", "rad"},
    rows::kAltitude,
    rows::kYaw,
    rows::kKp,
    rows::kKd,
};

void* LemniscateCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const mjf::plugin::Attributes attributes(ctx);
    LemniscateGuidance::Config config;
    config.bounds = ReadBounds(attributes);
    config.half_width = attributes.Number(kHalfWidth);
    config.omega = attributes.Number(kOmega);
    const auto center = attributes.Numbers(kCenter, 2);
    config.center = {center[0], center[1]};
    config.phase = attributes.Number(kPhase);
    config.altitude = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<LemniscateGuidance>{CheckVehicle(ctx), LemniscateGuidance(config)};
  });
}

}  // namespace

const mjfPlugin kLemniscate = LeaderPlugin<LemniscateGuidance>(
    "lemniscate", "leader figure-eight (Gerono), tracked by PD, command clamped to [a_min, a_max]",
    kLemniscateAttributes, LemniscateCreate);

}  // namespace mjf::guidance::adapter
