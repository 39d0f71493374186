// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/bang_bang.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;

BangBangGuidance::BangBangGuidance(const Config& config)
    : config_(config), envelope_(config.envelope, config.bounds) {
  if (!(config.dwell_min > 0.0) || !std::isfinite(config.dwell_min)) {
    Refuse("attribute 'dwell': the shortest dwell time must be > 0 s (got " +
           Num(config.dwell_min) + ")");
  }
  if (!(config.dwell_max >= config.dwell_min) || !std::isfinite(config.dwell_max)) {
    Refuse("attribute 'dwell': expected 'min max' with min <= max (got " + Num(config.dwell_min) +
           ", " + Num(config.dwell_max) + ")");
  }
  RequireFiniteAttribute(config.altitude, "altitude");
  RequireFiniteAttribute(config.yaw, "yaw");
  Reset();
}

double BangBangGuidance::Dwell(int axis, uint64_t index) const {
  return config_.dwell_min +
         (config_.dwell_max - config_.dwell_min) * HashUniform(config_.seed, 16 + axis, index);
}

void BangBangGuidance::Reset() {
  for (int axis = 0; axis < 2; ++axis) {
    sign_[axis] = HashUniform(config_.seed, 32 + axis, 0) < 0.5 ? -1 : 1;
    draws_[axis] = 0;
    switch_time_[axis] = Dwell(axis, draws_[axis]++);
  }
  last_time_ = 0;
}

GuidanceOutput BangBangGuidance::Update(double t, const Vec3& pos, const Vec3& vel) {
  if (t < last_time_) {
    Refuse("bang_bang: time went backwards (" + Num(t) + " < " + Num(last_time_) +
           " s); call Reset() to start again");
  }
  last_time_ = t;
  GuidanceOutput out;
  for (int axis = 0; axis < 2; ++axis) {
    const auto limits = envelope_.SpeedLimits(axis, pos[axis]);
    const double v = vel[axis];
    // A sign is forbidden when the speed toward that side already reaches its limit.
    auto forbidden = [&](int sign) { return sign > 0 ? v >= limits[0] : v <= -limits[1]; };
    while (t >= switch_time_[axis]) {  // dwell over: switch unless the other side is forbidden
      if (!forbidden(-sign_[axis])) sign_[axis] = -sign_[axis];
      switch_time_[axis] += Dwell(axis, draws_[axis]++);
    }
    if (forbidden(sign_[axis]) && !forbidden(-sign_[axis])) {  // envelope: switch now
      sign_[axis] = -sign_[axis];
      switch_time_[axis] = t + Dwell(axis, draws_[axis]++);
    }
    out.acc[axis] = sign_[axis] > 0 ? config_.bounds.max : config_.bounds.min;
    out.pos[axis] = pos[axis];
    out.vel[axis] = vel[axis];
  }
  out.pos[2] = config_.altitude;
  out.yaw = config_.yaw;
  return out;
}

}  // namespace mjf::guidance
