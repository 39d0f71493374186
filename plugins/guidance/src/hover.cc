// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/hover.hpp"

#include "check.hpp"

namespace mjf::guidance {

using check::RequireFinite;
using check::RequireGains;

HoverGuidance::HoverGuidance(const Config& config) : config_(config) {
  RequireGains(config.gains);
  for (double p : config.position) RequireFinite(p, "position");
  RequireFinite(config.yaw, "yaw");
}

GuidanceOutput HoverGuidance::Update(const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput out;
  out.pos = config_.position;
  out.yaw = config_.yaw;
  for (int i = 0; i < 2; ++i) {
    out.acc[i] = config_.gains.kp * (out.pos[i] - pos[i]) - config_.gains.kd * vel[i];
  }
  return out;
}

}  // namespace mjf::guidance
