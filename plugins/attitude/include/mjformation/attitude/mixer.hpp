// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Control allocation of a quadrotor: collective thrust and body torques <-> four rotor thrusts,
// built from the rotor geometry (site position and actuator gear), with saturation that keeps
// thrust first, then roll/pitch, then yaw.
#ifndef MJFORMATION_ATTITUDE_MIXER_HPP_
#define MJFORMATION_ATTITUDE_MIXER_HPP_

#include <Eigen/Dense>
#include <array>

#include "mjformation/attitude/types.hpp"

namespace mjf::attitude {

// One rotor: a force gear[0..2] * u along the rotor frame's axes applied at pos, plus the torque
// gear[3..5] * u, for a control u in [ctrl_min, ctrl_max] (N). The rotor frame must be aligned with
// the body frame (rotor sites without rotation).
struct RotorGeometry {
  Vec3 pos{};                    // m, from the centre of mass, body axes
  std::array<double, 6> gear{};  // force (0..2, -) and torque (3..5, m) per newton of control
  double ctrl_min = 0;           // N
  double ctrl_max = 0;           // N
};

// The wrench of the rotors, body frame: [thrust along body z (N), torque x, y, z (N m)].
using Wrench = Eigen::Vector4d;

class Mixer {
 public:
  static constexpr int kRotors = 4;

  // Throws std::invalid_argument when the allocation matrix is singular or ill-conditioned
  // (condition number above kMaxCondition) or a control range is empty.
  explicit Mixer(const std::array<RotorGeometry, kRotors>& rotors);

  static constexpr double kMaxCondition = 1e6;

  // B: wrench = B u, column k = what a unit control of rotor k does (thrust, torque x, y, z).
  const Eigen::Matrix4d& allocation() const { return allocation_; }
  const Eigen::Matrix4d& inverse() const { return inverse_; }
  double condition_number() const { return condition_; }

  struct Result {
    std::array<double, kRotors> ctrl{};  // N, within [ctrl_min, ctrl_max]
    bool thrust_saturated = false;       // the collective thrust was cut
    double roll_pitch_scale = 1;         // fraction of the roll/pitch torque delivered
    double yaw_scale = 1;                // fraction of the yaw torque delivered
  };

  // Rotor controls for a wanted wrench. Priority when saturating: collective thrust, then the
  // roll/pitch torque (scaled down together, direction kept), then the yaw torque.
  Result Mix(const Wrench& wanted) const;

 private:
  // Largest s in [0, 1] with base + s * delta inside the control ranges.
  double MaxScale(const Eigen::Vector4d& base, const Eigen::Vector4d& delta) const;

  Eigen::Matrix4d allocation_;
  Eigen::Matrix4d inverse_;
  Eigen::Vector4d ctrl_min_, ctrl_max_;
  double condition_ = 0;
};

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_MIXER_HPP_
