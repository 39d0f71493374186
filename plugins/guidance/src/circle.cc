// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/circle.hpp"

#include <cmath>
#include <stdexcept>

#include "check.hpp"

namespace mjf::guidance {

using check::RequireFinite;
using check::RequireGains;

CircleGuidance::CircleGuidance(const Config& config) : config_(config) {
  RequireGains(config.gains);
  if (!(config.radius >= 0)) throw std::invalid_argument("radius must be >= 0");
  RequireFinite(config.radius, "radius");
  RequireFinite(config.omega, "omega");
  RequireFinite(config.phase, "phase");
  RequireFinite(config.altitude, "altitude");
  RequireFinite(config.yaw, "yaw");
  RequireFinite(config.center[0], "center");
  RequireFinite(config.center[1], "center");
}

GuidanceOutput CircleGuidance::Reference(double t) const {
  const double r = config_.radius, w = config_.omega;
  const double angle = w * t + config_.phase;
  const double c = std::cos(angle), s = std::sin(angle);
  GuidanceOutput out;
  out.pos = {config_.center[0] + r * c, config_.center[1] + r * s, config_.altitude};
  out.vel = {-r * w * s, r * w * c, 0};
  out.acc = {-r * w * w * c, -r * w * w * s, 0};
  out.yaw = config_.yaw;
  return out;
}

GuidanceOutput CircleGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput out = Reference(t);
  for (int i = 0; i < 2; ++i) {
    out.acc[i] +=
        config_.gains.kp * (out.pos[i] - pos[i]) + config_.gains.kd * (out.vel[i] - vel[i]);
  }
  return out;
}

}  // namespace mjf::guidance
