// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/lemniscate.hpp"

#include <cmath>
#include <string>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;
using check::ValidateTracking;

LemniscateGuidance::LemniscateGuidance(const Config& config) : config_(config) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  RequireFiniteAttribute(config.omega, "omega");
  RequireFiniteAttribute(config.phase, "phase");
  RequireFiniteAttribute(config.center[0], "center");
  RequireFiniteAttribute(config.center[1], "center");
  if (!(config.half_width > 0.0) || !std::isfinite(config.half_width)) {
    Refuse("attribute 'half_width' must be > 0 m (got " + Num(config.half_width) + ")");
  }
  // Peak reference accelerations: A w^2 on x, 2 A w^2 on y, both signs (sines).
  const double peak = 2.0 * config.half_width * config.omega * config.omega;
  if (!(peak <= config.bounds.max && -peak >= config.bounds.min)) {
    Refuse(
        "attributes 'half_width', 'omega': the figure-eight needs accelerations up to +-2 A "
        "w^2 = +-" +
        Num(peak) + " m/s^2 on y, outside [a_min, a_max] = [" + Num(config.bounds.min) + ", " +
        Num(config.bounds.max) + "]; lower omega or half_width");
  }
}

GuidanceOutput LemniscateGuidance::Reference(double t) const {
  const double a = config_.half_width, w = config_.omega, th = w * t + config_.phase;
  GuidanceOutput out;
  out.pos = {config_.center[0] + a * std::sin(th), config_.center[1] + 0.5 * a * std::sin(2 * th),
             config_.altitude};
  out.vel = {a * w * std::cos(th), a * w * std::cos(2 * th), 0};
  out.acc = {-a * w * w * std::sin(th), -2.0 * a * w * w * std::sin(2 * th), 0};
  out.yaw = config_.yaw;
  return out;
}

GuidanceOutput LemniscateGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  return TrackClamped(Reference(t), pos, vel, config_.gains, config_.bounds);
}

}  // namespace mjf::guidance
