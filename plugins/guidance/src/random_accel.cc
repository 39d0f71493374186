// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/random_accel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

RandomAccelGuidance::RandomAccelGuidance(const Config& config)
    : config_(config), envelope_(config.envelope, config.bounds) {
  if (!(config.correlation_time > 0.0) || !std::isfinite(config.correlation_time)) {
    Refuse("attribute 'correlation_time' must be > 0 s (got " + Num(config.correlation_time) + ")");
  }
  RequireFiniteAttribute(config.altitude, "altitude");
  RequireFiniteAttribute(config.yaw, "yaw");
}

double RandomAccelGuidance::Signal(int axis, double t) const {
  const double x = std::max(t, 0.0) / config_.correlation_time;
  const double k = std::floor(x);
  const uint64_t index = static_cast<uint64_t>(k);
  const double range = config_.bounds.max - config_.bounds.min;
  const double a0 = config_.bounds.min + range * HashUniform(config_.seed, axis, index);
  const double a1 = config_.bounds.min + range * HashUniform(config_.seed, axis, index + 1);
  const double blend = 0.5 * (1.0 - std::cos(kPi * (x - k)));  // in [0, 1], monotone
  return config_.bounds.Clamp(a0 + (a1 - a0) * blend);
}

GuidanceOutput RandomAccelGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput out;
  for (int axis = 0; axis < 2; ++axis) {
    const auto allowed = envelope_.Allowed(axis, pos[axis], vel[axis]);
    out.acc[axis] = std::clamp(Signal(axis, t), allowed[0], allowed[1]);
    out.pos[axis] = pos[axis];
    out.vel[axis] = vel[axis];
  }
  out.pos[2] = config_.altitude;
  out.yaw = config_.yaw;
  return out;
}

}  // namespace mjf::guidance
