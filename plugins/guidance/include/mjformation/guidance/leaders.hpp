// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Maneuvering (non-cooperative) leaders: guidance laws whose horizontal acceleration command
// stays, per axis, exactly inside [a_min, a_max] (the paper's Assumption 1, u_min <= u_0 <=
// u_max, Remark 1). No MuJoCo, no plugin ABI: state in, command out. Deterministic: the same
// seed and the same sequence of calls give the same commands.
#ifndef MJFORMATION_GUIDANCE_LEADERS_HPP_
#define MJFORMATION_GUIDANCE_LEADERS_HPP_

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mjformation/guidance/guidance.hpp"

namespace mjf::guidance {

// Per-axis acceleration bounds (m/s^2) applied to x and y alike (Assumption 1).
struct AccelBounds {
  double min = -1.0;  // 'a_min'
  double max = 1.0;   // 'a_max'
  // a_min < a_max, both finite; throws std::invalid_argument naming the keys.
  void Validate() const;
  // Also 0 strictly inside: a law that must brake (speed limit, area) needs both signs.
  void ValidateBothSigns(const char* why) const;
  double Clamp(double a) const { return a < min ? min : (a > max ? max : a); }
};

// A uniform number in [0, 1) that depends only on (seed, stream, index) (splitmix64 mixing):
// random signals become pure functions of time, identical whatever the call pattern.
double HashUniform(uint64_t seed, uint64_t stream, uint64_t index);

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

// random_accel: a smooth random acceleration per axis. Knots every `correlation_time` seconds
// hold uniform values in [a_min, a_max] (fill the bounds); between knots a cosine blend
// a = a_k + (a_k+1 - a_k) (1 - cos(pi u)) / 2 is monotone, so the signal never leaves the knots'
// range and is C1 (band-limited to about 1 / (2 correlation_time) Hz). The envelope then clips
// it to keep the speed limit and the area.
class RandomAccelGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    Envelope::Config envelope;
    double correlation_time = 2.0;  // 'correlation_time', s, knot spacing (> 0)
    uint64_t seed = 1;              // 'seed'
    double altitude = 5.0;          // m
    double yaw = 0.0;               // rad
  };
  explicit RandomAccelGuidance(const Config& config);
  // The unclipped random signal on one axis at time t (s): inside [a_min, a_max].
  double Signal(int axis, double t) const;
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;

 private:
  Config config_;
  Envelope envelope_;
};

// bang_bang: per axis the acceleration is a_min or a_max, switching after dwell times drawn
// uniformly in [dwell_min, dwell_max] (seeded); the envelope forces an early switch when the
// speed limit or the area would be broken (the command is still one of the two bounds).
// Stateful: Update must be called with non-decreasing t (Reset() to start again).
class BangBangGuidance {
 public:
  struct Config {
    AccelBounds bounds;
    Envelope::Config envelope;
    double dwell_min = 0.5;  // 'dwell' first number, s (> 0)
    double dwell_max = 3.0;  // 'dwell' second number, s (>= dwell_min)
    uint64_t seed = 1;       // 'seed'
    double altitude = 5.0;   // m
    double yaw = 0.0;        // rad
  };
  explicit BangBangGuidance(const Config& config);
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel);
  void Reset();

 private:
  double Dwell(int axis, uint64_t index) const;
  Config config_;
  Envelope envelope_;
  std::array<int, 2> sign_{};            // +1: a_max, -1: a_min
  std::array<double, 2> switch_time_{};  // s, end of the current dwell
  std::array<uint64_t, 2> draws_{};      // dwell times drawn so far
  double last_time_ = 0;
};

// A reference (position, velocity, acceleration at t) tracked with the PD law of the circle and
// the command clamped per axis to the bounds: a = clamp(a_ref + kp (p_ref - p) + kd (v_ref - v)).
GuidanceOutput TrackClamped(const GuidanceOutput& reference, const Vec3& pos, const Vec3& vel,
                            const TrackingGains& gains, const AccelBounds& bounds);

// lemniscate: the figure-eight of Gerono, x = cx + A sin(w t + phase),
// y = cy + (A / 2) sin(2 (w t + phase)); peak reference accelerations A w^2 (x), 2 A w^2 (y),
// which must lie inside the bounds.
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

 private:
  Config config_;
};

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

// waypoints: a smooth path through the given points at about `speed` (segment time = length /
// speed), starting and ending at rest (or looping). Refused when a segment would need an
// acceleration outside the bounds ("too close for the bounds at this speed").
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
  const HermitePath& path() const { return path_; }

 private:
  static HermitePath Build(const Config& config);
  Config config_;
  HermitePath path_;
};

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

// trajectory: a recorded path interpolated by a Catmull-Rom C1 spline; altitude from z when the
// file has it. The command is clamped to the bounds.
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

 private:
  Config config_;
  bool has_z_;
  HermitePath path_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_LEADERS_HPP_
