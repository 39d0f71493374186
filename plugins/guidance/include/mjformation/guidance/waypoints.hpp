// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// waypoints: a leader on a smooth path through given points, inside the acceleration bounds.
#ifndef MJFORMATION_GUIDANCE_WAYPOINTS_HPP_
#define MJFORMATION_GUIDANCE_WAYPOINTS_HPP_

#include <array>
#include <vector>

#include "mjformation/guidance/bounds.hpp"
#include "mjformation/guidance/hermite_path.hpp"

namespace mjf::guidance {

// A smooth path through the given points at about `speed` (segment time = length / speed),
// starting and ending at rest (or looping). Refused when a segment would need an acceleration
// outside the bounds ("too close for the bounds at this speed").
class WaypointGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    std::vector<std::array<double, 2>> points;  // 'points' "x0 y0 x1 y1 ...", m
    double speed = 2.0;                         // 'speed', m/s
    bool loop = false;                          // 'loop'
    double altitude = 5.0;
    double yaw = 0.0;
    TrackingGains gains;
  };
  explicit WaypointGuidance(const Config& config);
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a function of t and the state
  const HermitePath& path() const { return path_; }

 private:
  static HermitePath Build(const Config& config);
  Config config_;
  HermitePath path_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_WAYPOINTS_HPP_
