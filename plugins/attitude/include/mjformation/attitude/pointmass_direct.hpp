// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The attitude "loop" of an ideal double integrator (mjcf/pointmass.xml): force = m * command,
// plus gravity compensation and a PD altitude hold on z.
#ifndef MJFORMATION_ATTITUDE_POINTMASS_DIRECT_HPP_
#define MJFORMATION_ATTITUDE_POINTMASS_DIRECT_HPP_

#include "mjformation/attitude/types.hpp"

namespace mjf::attitude {

class PointMassDirect {
 public:
  struct Gains {
    double kp_z = 6;  // 1/s^2
    double kd_z = 5;  // 1/s
  };
  // Throws std::invalid_argument on a non-positive mass or gravity, or a negative gain.
  PointMassDirect(const Gains& gains, double mass, double gravity);

  // World-frame force (N) on the fx, fy, fz actuators:
  //   f_xy = m acc_xy,  f_z = m (g + acc_z + kp_z (z_ref - z) + kd_z (vz_ref - vz)).
  Vec3 Update(const VehicleState& state, const Setpoint& setpoint) const;
  template <typename Visit>
  void VisitState(Visit&) {}  // no state: a pure function of state and setpoint

 private:
  Gains gains_;
  double mass_, gravity_;
};

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_POINTMASS_DIRECT_HPP_
