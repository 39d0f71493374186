// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// trajectory: a leader on a recorded path read from a CSV file.
#ifndef MJFORMATION_GUIDANCE_TRAJECTORY_HPP_
#define MJFORMATION_GUIDANCE_TRAJECTORY_HPP_

#include <string>
#include <vector>

#include "mjformation/guidance/bounds.hpp"
#include "mjformation/guidance/hermite_path.hpp"

namespace mjf::guidance {

// A recorded path: rows of t, x, y (and optionally z).
struct TrajectoryTable {
  std::vector<double> t;
  std::vector<Vec3> pos;
  bool has_z = false;
};
// Reads a CSV of "t,x,y[,z]" rows (an optional header line, '#' comments, blank lines skipped).
// Throws std::invalid_argument naming the file, the line and the reason: unreadable file,
// wrong column count, a value that is not a finite number, t not strictly increasing, fewer than
// two rows.
TrajectoryTable ReadTrajectoryCsv(const std::string& path);

// A recorded path interpolated by a Catmull-Rom C1 spline; altitude from z when the file has
// it. The command is clamped to the bounds.
class TrajectoryGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    double time_offset = 0.0;  // 'time_offset', s: the path's time at t = 0
    double altitude = 5.0;     // used when the file has no z
    double yaw = 0.0;
    TrackingGains gains;
  };
  TrajectoryGuidance(const Config& config, const TrajectoryTable& table);
  GuidanceOutput Reference(double t) const;
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a function of t and the state

 private:
  Config config_;
  bool has_z_;
  HermitePath path_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_TRAJECTORY_HPP_
