// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/guidance/waypoints.hpp"

#include <cmath>
#include <string>

#include "check.hpp"

namespace mjf::guidance {

using check::Num;
using check::Refuse;
using check::RequireFiniteAttribute;
using check::ValidateTracking;

HermitePath WaypointGuidance::Build(const Config& config) {
  config.bounds.Validate();
  ValidateTracking(config.gains, config.altitude, config.yaw);
  if (!(config.speed > 0.0) || !std::isfinite(config.speed)) {
    Refuse("attribute 'speed' must be > 0 m/s (got " + Num(config.speed) + ")");
  }
  if (config.points.size() < 2) Refuse("attribute 'points': at least two waypoints 'x y' needed");
  std::vector<Vec3> points;
  for (const auto& p : config.points) {
    RequireFiniteAttribute(p[0], "points");
    RequireFiniteAttribute(p[1], "points");
    points.push_back({p[0], p[1], config.altitude});
  }
  if (config.loop) points.push_back(points.front());
  std::vector<double> times = {0.0};
  for (size_t k = 1; k < points.size(); ++k) {
    const double length =
        std::hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
    if (!(length > 0.0)) {
      Refuse("attribute 'points': waypoints " + std::to_string(k - 1) + " and " +
             std::to_string(k % config.points.size()) + " coincide");
    }
    times.push_back(times.back() + length / config.speed);
  }
  HermitePath path(times, points, CatmullRomVelocities(times, points, config.loop), config.loop);
  // The acceleration is linear on each segment: its extremes are at the knots (exact check).
  for (size_t k = 0; k < path.segments(); ++k) {
    for (const Vec3& a : path.SegmentAcc(k)) {
      for (int i = 0; i < 2; ++i) {
        if (a[i] > config.bounds.max || a[i] < config.bounds.min) {
          Refuse("attribute 'points': waypoints " + std::to_string(k) + " -> " +
                 std::to_string((k + 1) % config.points.size()) +
                 " are too close for the bounds at 'speed' = " + Num(config.speed) +
                 " m/s: the smooth path needs a_" + (i == 0 ? "x" : "y") + " = " + Num(a[i]) +
                 " m/s^2, outside [a_min, a_max] = [" + Num(config.bounds.min) + ", " +
                 Num(config.bounds.max) + "]; space them further apart or lower 'speed'");
        }
      }
    }
  }
  return path;
}

WaypointGuidance::WaypointGuidance(const Config& config) : config_(config), path_(Build(config)) {}

GuidanceOutput WaypointGuidance::Update(double t, const Vec3& pos, const Vec3& vel) const {
  GuidanceOutput ref = path_.Evaluate(t);
  ref.pos[2] = config_.altitude;
  ref.vel[2] = ref.acc[2] = 0.0;
  ref.yaw = config_.yaw;
  return TrackClamped(ref, pos, vel, config_.gains, config_.bounds);
}

}  // namespace mjf::guidance
