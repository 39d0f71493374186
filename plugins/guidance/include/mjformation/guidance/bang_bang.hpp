// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// bang_bang: a maneuvering leader whose acceleration is always one of its two bounds.
#ifndef MJFORMATION_GUIDANCE_BANG_BANG_HPP_
#define MJFORMATION_GUIDANCE_BANG_BANG_HPP_

#include <array>
#include <cstdint>

#include "mjformation/guidance/bounds.hpp"
#include "mjformation/guidance/envelope.hpp"

namespace mjf::guidance {

// Per axis the acceleration is a_min or a_max, switching after dwell times drawn uniformly in
// [dwell_min, dwell_max] (seeded); the envelope forces an early switch when the speed limit or
// the area would be broken (the command is still one of the two bounds).
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
  // The current dwell per axis and the dwell draws so far (drawn from (seed, index), so the
  // counter is the random stream's state), and the last time (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(sign_, switch_time_, draws_, last_time_);
  }

 private:
  double Dwell(int axis, uint64_t index) const;
  Config config_;
  Envelope envelope_;
  std::array<int, 2> sign_{};            // +1: a_max, -1: a_min
  std::array<double, 2> switch_time_{};  // s, end of the current dwell
  std::array<uint64_t, 2> draws_{};      // dwell times drawn so far
  double last_time_ = 0;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_BANG_BANG_HPP_
