// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// hover: holds a point (no MuJoCo, no plugin ABI).
#ifndef MJFORMATION_GUIDANCE_HOVER_HPP_
#define MJFORMATION_GUIDANCE_HOVER_HPP_

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance {

// Holds a point: a = kp (p_ref - p) + kd (0 - v) in x and y; altitude and yaw references.
class HoverGuidance {
 public:
  struct Config {
    Vec3 position{0, 0, 1};  // m
    double yaw = 0;          // rad
    TrackingGains gains;
  };
  explicit HoverGuidance(const Config& config);
  GuidanceOutput Update(const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a function of the state

 private:
  Config config_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_HOVER_HPP_
