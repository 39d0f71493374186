// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// hover: the adapter of HoverGuidance (holds a point, by default the initial position).
#include "mjformation/guidance/hover.hpp"

#include <string>

#include "adapter.hpp"

namespace mjf::guidance::adapter {
namespace {

using mjf::plugin::Attributes;
using mjf::plugin::ConfigError;

const mjfAttribute kHoverAttributes[] = {
    {kPosition, "", "m: point to hold 'x y z' (empty: the vehicle's initial position)"},
    {kAltitude, "", "m: overrides the held z when given"},
    rows::kYaw,
    rows::kKp,
    {kKd, "2", "1/s: velocity gain"},
};

// HoverGuidance holds a point whatever the time: the family's Update(t, pos, vel) over it.
struct HoverLaw {
  GuidanceOutput Update(double /*t*/, const Vec3& pos, const Vec3& vel) const {
    return guidance.Update(pos, vel);
  }
  template <typename Visit>
  void VisitState(Visit& visit) {
    guidance.VisitState(visit);
  }
  HoverGuidance guidance;
};

void* HoverCreate(const mjfCreateContext* ctx) {
  return mjf::plugin::CreateOrExplain(ctx, [ctx]() -> void* {
    const Attributes attributes(ctx);
    HoverGuidance::Config config;
    if (!Blank(attributes.String(kPosition))) {
      const auto p = attributes.Numbers(kPosition, 3);
      config.position = {p[0], p[1], p[2]};
    } else if (ctx->initial_pos) {
      config.position = Get(ctx->initial_pos);
    } else {
      throw ConfigError(std::string("attribute '") + kPosition +
                        "' is needed: the host gave no initial position");
    }
    if (!Blank(attributes.String(kAltitude))) config.position[2] = attributes.Number(kAltitude);
    config.yaw = attributes.Number(kYaw);
    config.gains = ReadGains(attributes);
    return new LeaderInstance<HoverLaw>{CheckVehicle(ctx), HoverLaw{HoverGuidance(config)}};
  });
}

}  // namespace

const mjfPlugin kHover = LeaderPlugin<HoverLaw>(
    "hover", "holds a point (default: the initial position): a = kp (p_ref - p) - kd v",
    kHoverAttributes, HoverCreate);

}  // namespace mjf::guidance::adapter
