// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The speed limit and the area the random leaders (random_accel, bang_bang) keep without
// leaving their acceleration bounds.
#ifndef MJFORMATION_GUIDANCE_ENVELOPE_HPP_
#define MJFORMATION_GUIDANCE_ENVELOPE_HPP_

#include <array>

#include "mjformation/guidance/bounds.hpp"

namespace mjf::guidance {

// Keeps a double integrator with per-axis acceleration in [a_min, a_max] inside a box and under
// a speed limit without leaving the bounds: toward each wall the allowed speed is
// v_lim(g) = min(speed_max, sqrt(2 b (g - margin))) (g: distance to the wall, b half the
// braking capacity), and the allowed acceleration ramps from the bound to the opposite bound as
// the speed crosses v_lim - ramp .. v_lim + ramp. margin = ramp^2 / b covers the lag.
class Envelope {
 public:
  struct Config {
    double speed_max = 3.0;                    // 'speed_max', m/s, per axis
    std::array<double, 2> area_min{-40, -40};  // 'area' x_min y_min, m
    std::array<double, 2> area_max{40, 40};    // 'area' x_max y_max, m
    double ramp = 0.3;                         // 'ramp', m/s
  };
  // Throws std::invalid_argument when the box is too small for the bounds (naming 'area').
  Envelope(const Config& config, const AccelBounds& bounds);
  // Largest speed allowed toward +axis (first) and toward -axis (second) at position p.
  std::array<double, 2> SpeedLimits(int axis, double p) const;
  // Allowed acceleration interval [lo, hi] inside the bounds at state (p, v) on one axis.
  std::array<double, 2> Allowed(int axis, double p, double v) const;
  double margin() const { return margin_; }
  const Config& config() const { return config_; }

 private:
  Config config_;
  AccelBounds bounds_;
  double margin_ = 0;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_ENVELOPE_HPP_
