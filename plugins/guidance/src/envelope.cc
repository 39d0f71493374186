// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;

namespace {

// Allowed acceleration toward +: `up` below v_lim - ramp, 0 at v_lim, -down above v_lim + ramp.
double UpperLimit(double v, double v_lim, double up, double down, double ramp) {
  const double x = (v - v_lim) / ramp;  // -1 .. 1 across the ramp
  if (x <= -1.0) return up;
  if (x >= 1.0) return -down;
  return x < 0.0 ? -x * up : -x * down;
}

}  // namespace

Envelope::Envelope(const Config& config, const AccelBounds& bounds)
    : config_(config), bounds_(bounds) {
  bounds.ValidateBothSigns("to brake for the speed limit and the area");
  if (!(config.ramp > 0.0) || !std::isfinite(config.ramp)) {
    Refuse("attribute 'ramp' must be > 0 (got " + Num(config.ramp) + ")");
  }
  if (!(config.speed_max > 2.0 * config.ramp) || !std::isfinite(config.speed_max)) {
    Refuse("attribute 'speed_max' must be > 2 ramp = " + Num(2.0 * config.ramp) + " m/s (got " +
           Num(config.speed_max) + ")");
  }
  const double b = 0.5 * std::min(-bounds.min, bounds.max);  // half the weaker braking
  margin_ = config.ramp * config.ramp / b;
  for (int axis = 0; axis < 2; ++axis) {
    RequireFiniteAttribute(config.area_min[axis], "area");
    RequireFiniteAttribute(config.area_max[axis], "area");
    const double width = config.area_max[axis] - config.area_min[axis];
    if (!(width > 4.0 * margin_)) {
      Refuse(std::string("attribute 'area': the ") + (axis == 0 ? "x" : "y") + " extent " +
             Num(width) + " m must exceed 4 x the braking margin ramp^2 / b = " + Num(margin_) +
             " m (b = half the weaker bound) to turn around inside it");
    }
  }
}

std::array<double, 2> Envelope::SpeedLimits(int axis, double p) const {
  // Toward + the vehicle brakes with a_min, toward - with a_max; half of it in the envelope so
  // the ramp can follow the shrinking limit.
  const double gap_up = std::max(config_.area_max[axis] - margin_ - p, 0.0);
  const double gap_down = std::max(p - config_.area_min[axis] - margin_, 0.0);
  return {std::min(config_.speed_max, std::sqrt(2.0 * 0.5 * -bounds_.min * gap_up)),
          std::min(config_.speed_max, std::sqrt(2.0 * 0.5 * bounds_.max * gap_down))};
}

std::array<double, 2> Envelope::Allowed(int axis, double p, double v) const {
  const auto limits = SpeedLimits(axis, p);
  const double ramp = config_.ramp;
  const double hi = UpperLimit(v, limits[0], bounds_.max, -bounds_.min, ramp);
  const double lo = -UpperLimit(-v, limits[1], -bounds_.min, bounds_.max, ramp);
  if (lo > hi) {  // both walls close (only in a box near its minimum size): split the difference
    const double mid = bounds_.Clamp(0.5 * (lo + hi));
    return {mid, mid};
  }
  return {bounds_.Clamp(lo), bounds_.Clamp(hi)};
}

}  // namespace mjf::guidance
