// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Guidance laws of one vehicle (no MuJoCo, no plugin ABI): a reference trajectory and a PD
// tracking law with acceleration feedforward, giving the horizontal acceleration command of the
// setpoint bus plus the altitude and yaw references the attitude loop holds.
#ifndef MJFORMATION_GUIDANCE_GUIDANCE_HPP_
#define MJFORMATION_GUIDANCE_GUIDANCE_HPP_

#include <array>

namespace mjf::guidance {

using Vec3 = std::array<double, 3>;

// What a guidance law writes on the setpoint bus (mjfSetpoint without the sliding diagnostics).
struct GuidanceOutput {
  Vec3 acc{};      // m/s^2, world: x, y command (feedforward + feedback); z feedforward
  Vec3 pos{};      // m, reference position (z: altitude setpoint)
  Vec3 vel{};      // m/s, reference velocity
  double yaw = 0;  // rad
};

struct TrackingGains {
  double kp = 1;  // 1/s^2, position error -> acceleration
  double kd =
      2;  // 1/s, velocity error -> acceleration (kp = 1, kd = 2: critically damped, 1 rad/s)
};

// The paper's leader (section 6): p(t) = c + r [cos(w t + phase), sin(w t + phase)], constant
// altitude; command a = a_ref + kp (p_ref - p) + kd (v_ref - v) per horizontal axis.
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

 private:
  Config config_;
};

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

 private:
  Config config_;
};

}  // namespace mjf::guidance

#endif  // MJFORMATION_GUIDANCE_GUIDANCE_HPP_
