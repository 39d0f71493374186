// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Control allocation of a quadrotor: collective thrust and body torques <-> four rotor thrusts,
// built from the rotor geometry (site position and actuator gear), with a choice of what
// saturation keeps first (Priority): yaw is always given up first.
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

  // The largest torque (N m, >= 0) about body axis `axis` (0 x, 1 y, 2 z) the rotors deliver,
  // in either direction, while they also give the collective `thrust` (hover), no other torque.
  double TorqueAuthority(int axis, double thrust) const;

  // What Mix() keeps when the rotors cannot deliver the whole wrench.
  enum class Priority {
    // Collective thrust (scaled into range), then roll/pitch (scaled together), then yaw. At full
    // thrust no rotor can speed up, so roll/pitch authority is lost (pd_cascade's historic mode).
    kThrustFirst,
    // Roll/pitch torque (scaled together, direction kept, only as far as the rotor ranges are too
    // narrow for it at ANY collective), then the collective moved as little as possible to make
    // room for it, then yaw. The vehicle keeps its attitude and gives up some thrust (PX4's
    // desaturation idea): a quadrotor that loses attitude authority flips.
    kRollPitchFirst,
  };

  struct Result {
    std::array<double, kRotors> ctrl{};  // N, within [ctrl_min, ctrl_max]
    bool thrust_saturated = false;       // the collective thrust was changed (cut or raised)
    double thrust = 0;                   // N, collective thrust delivered
    double roll_pitch_scale = 1;         // fraction of the roll/pitch torque delivered
    double yaw_scale = 1;                // fraction of the yaw torque delivered
  };

  // Rotor controls for a wanted wrench; what is kept when saturating: see Priority.
  Result Mix(const Wrench& wanted, Priority priority = Priority::kThrustFirst) const;

 private:
  // Largest s in [0, 1] with base + s * delta inside the control ranges.
  double MaxScale(const Eigen::Vector4d& base, const Eigen::Vector4d& delta) const;
  // Collectives t (N) with t * inverse_.col(0) + extra inside the control ranges: [*lo, *hi];
  // false when there is none.
  bool ThrustInterval(const Eigen::Vector4d& extra, double* lo, double* hi) const;
  Result MixRollPitchFirst(const Wrench& wanted) const;

  Eigen::Matrix4d allocation_;
  Eigen::Matrix4d inverse_;
  Eigen::Vector4d ctrl_min_, ctrl_max_;
  double condition_ = 0;
};

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_MIXER_HPP_
