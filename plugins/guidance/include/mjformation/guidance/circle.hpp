// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// circle: the paper's leader (section 6), a reference circle tracked by a PD law with
// acceleration feedforward, giving the horizontal acceleration command of the setpoint bus plus
// the altitude and yaw references the attitude loop holds.
#ifndef MJFORMATION_GUIDANCE_CIRCLE_HPP_
#define MJFORMATION_GUIDANCE_CIRCLE_HPP_

#include <array>

#include "mjformation/guidance/types.hpp"

namespace mjf::guidance {

// p(t) = c + r [cos(w t + phase), sin(w t + phase)], constant altitude; command
// a = a_ref + kp (p_ref - p) + kd (v_ref - v) per horizontal axis.
class CircleGuidance {
 public:
  struct Config {
    std::array<double, 2> center{0, 0};  // m
    double radius = 20;                  // m (paper: r_l = 20 m)
    double omega = 0.157;                // rad/s (paper: w_l = 0.157 rad/s), > 0: counter-clockwise
    double phase = 0;                    // rad
    double altitude = 5;                 // m
    double yaw = 0;                      // rad
    TrackingGains gains;
  };
  // Throws std::invalid_argument on a negative radius or gain, or a non-finite value.
  explicit CircleGuidance(const Config& config);

  // The reference alone at time t (s): acc = a_ref, pos, vel, yaw.
  GuidanceOutput Reference(double t) const;
  // The reference and the tracking command for a vehicle at pos (m), vel (m/s).
  GuidanceOutput Update(double t, const Vec3& pos, const Vec3& vel) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a function of t and the state

 private:
  Config config_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_CIRCLE_HPP_
