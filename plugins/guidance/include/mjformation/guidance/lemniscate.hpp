// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// lemniscate: a leader on a figure-eight, its command clamped to the acceleration bounds.
#ifndef MJFORMATION_GUIDANCE_LEMNISCATE_HPP_
#define MJFORMATION_GUIDANCE_LEMNISCATE_HPP_

#include <array>

#include "mjformation/guidance/bounds.hpp"

namespace mjf::guidance {

// The figure-eight of Gerono, x = cx + A sin(w t + phase), y = cy + (A / 2) sin(2 (w t + phase));
// peak reference accelerations A w^2 (x), 2 A w^2 (y), which must lie inside the bounds.
class LemniscateGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    std::array<double, 2> center{0, 0};  // m
    double half_width = 20.0;            // 'half_width', A, m
    double omega = 0.15;                 // rad/s
    double phase = 0.0;                  // rad
    double altitude = 5.0;
    double yaw = 0.0;
    TrackingGains gains;
  };
  explicit LemniscateGuidance(const Config& config);
  GuidanceOutput Reference(double t) const;
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a function of t and the state

 private:
  Config config_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_LEMNISCATE_HPP_
