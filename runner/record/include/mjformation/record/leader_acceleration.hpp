// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The leader's true acceleration, measured from MuJoCo rather than taken from the guidance
// plugin's intent, checked against Assumption 1 (u_min <= u_0 <= u_max per axis, the bounds
// the formation plugin was told). O(1) per step, nothing grows with run length.
#ifndef MJFORMATION_RECORD_LEADER_ACCELERATION_HPP_
#define MJFORMATION_RECORD_LEADER_ACCELERATION_HPP_

#include <array>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace mjf::runner {

class Simulation;

class LeaderAccelerationMonitor {
 public:
  // Bounds: the formation plugin's u_min/u_max attributes, else the leader plugin's
  // a_min/a_max, else none (then only min/max are summarised).
  explicit LeaderAccelerationMonitor(const Simulation& sim);
  // Every physics step, after the sensors are read: a = (v_k - v_k-1) / dt of the leader's
  // velocity sensor, the acceleration over the step just taken. MuJoCo's semi-implicit Euler
  // sets v_k = v_k-1 + dt qacc, so for a translating body this is its acceleration exactly.
  void Step(const Simulation& sim);
  // The latest measured horizontal acceleration (m/s^2); NaN before the second step.
  const std::array<double, 2>& current() const { return current_; }
  // summary.json "leader_acceleration": per-axis min/max, the bounds and where they come from,
  // the fraction of time outside them, the largest excess beyond them and the first time
  // Assumption 1 is broken (null: never).
  nlohmann::ordered_json Summary() const;
  // The last velocity and the running extremes and counts, both ways (checkpoints).
  template <typename Archive>
  void VisitState(Archive& a) {
    a(have_previous_, previous_vel_, current_, min_, max_, samples_, outside_, max_excess_);
    a(first_violation_time_);
  }

  // Tolerance on the bounds (m/s^2): the finite difference of a body commanded exactly at a
  // bound differs from it by round-off (~1e-13); 1e-6 is far above that and far below any
  // violation that matters.
  static constexpr double kTolerance = 1e-6;

 private:
  double dt_;
  bool have_bounds_ = false;
  double u_min_ = 0, u_max_ = 0;
  std::string bounds_source_;
  bool have_previous_ = false;
  std::array<double, 2> previous_vel_{};
  std::array<double, 2> current_;
  std::array<double, 2> min_, max_;
  long samples_ = 0, outside_ = 0;
  double max_excess_ = -std::numeric_limits<double>::infinity();
  double first_violation_time_ = -1;
};

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_LEADER_ACCELERATION_HPP_
