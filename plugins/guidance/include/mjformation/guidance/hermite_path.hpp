// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The C1 spline the waypoints and trajectory leaders follow.
#ifndef MJFORMATION_GUIDANCE_HERMITE_PATH_HPP_
#define MJFORMATION_GUIDANCE_HERMITE_PATH_HPP_

#include <array>
#include <cstddef>
#include <vector>

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance {

// A C1 path through timed points: cubic Hermite segments (acceleration linear on each segment,
// so its extremes are at the knots). Before the first time it holds the first point, after the
// last the last point (or wraps around when periodic). z optional.
class HermitePath {
 public:
  // times strictly increasing, positions [k] = {x, y, z}, velocities at the knots.
  HermitePath(std::vector<double> times, std::vector<Vec3> positions, std::vector<Vec3> velocities,
              bool periodic);
  GuidanceOutput Evaluate(double t) const;  // pos, vel, acc (yaw 0)
  // Largest and smallest acceleration of each axis over the whole path (exact: at the knots).
  std::array<double, 3> max_acc() const;
  std::array<double, 3> min_acc() const;
  double duration() const { return times_.back() - times_.front(); }
  // Segment k's acceleration at its start (s = 0) and its end (s = 1), per axis.
  std::array<Vec3, 2> SegmentAcc(size_t k) const;
  size_t segments() const { return times_.size() - 1; }

 private:
  std::vector<double> times_;
  std::vector<Vec3> pos_, vel_;
  bool periodic_;
};

// Knot velocities of a Catmull-Rom spline through timed points: (p_k+1 - p_k-1) / (t_k+1 -
// t_k-1) inside; zero at the ends (start and stop at rest) unless periodic.
std::vector<Vec3> CatmullRomVelocities(const std::vector<double>& times,
                                       const std::vector<Vec3>& points, bool periodic);

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_HERMITE_PATH_HPP_
