// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The inner loop of the paper's two-loop scheme (Fig. 2, Fig. 7): a horizontal acceleration
// command becomes roll and pitch references through the hover-linearised model (9); a PD loop
// on roll and pitch and a PD loop on yaw give body torques; a PID loop holds the altitude; the
// mixer turns thrust and torques into four rotor thrusts.
//
// J. Wang, L. Han, X. Dong et al., Aerosp. Sci. Technol. 111 (2021) 106549, eq. (9), z up:
//   x'' = g (theta cos psi + phi sin psi),  y'' = g (theta sin psi - phi cos psi)
// (the small-angle limit of a = (T / m) R e_z - g e_z, R = Rz(psi) Ry(theta) Rx(phi)).
#ifndef MJFORMATION_ATTITUDE_PD_CASCADE_HPP_
#define MJFORMATION_ATTITUDE_PD_CASCADE_HPP_

#include "mjformation/attitude/mixer.hpp"
#include "mjformation/attitude/types.hpp"

namespace mjf::attitude {

class PdCascade {
 public:
  struct Gains {
    // rad, limit on the norm of (roll, pitch) references; 0 = derived (Resolve): kNominalTiltMax,
    // lowered to the vehicle's torque authority (AuthorityTiltLimit, types.hpp).
    double tilt_max = 0;
    // Roll/pitch PD, per unit inertia; 0 = derived (Resolve): kNominalKpAtt and kNominalKdAtt,
    // lowered together when the vehicle's torque authority cannot follow them.
    double kp_att = 0;  // 1/s^2, roll/pitch: angular acceleration per rad of error
    double kd_att = 0;  // 1/s, roll/pitch: angular acceleration per rad/s of body rate
    double kp_yaw = 9;  // 1/s^2
    double kd_yaw = 6;  // 1/s
    double kp_z = 6;    // 1/s^2, altitude
    double ki_z = 2;    // 1/s^3
    double kd_z = 5;    // 1/s
    double imax_z = 2;  // m/s^2, bound on the altitude integrator's acceleration
    // The two large-tilt fixes (docs/DISCUSSION.md, "Why pd_cascade flips"); off by default so
    // the experiments' results stay as published. Both are needed above kMaxTiltUnfixed.
    bool euler_rate_damping = false;  // damp the Euler-angle rates, not the body rates p, q
    Mixer::Priority allocation = Mixer::Priority::kThrustFirst;
  };
  // Largest tilt_max accepted without both fixes: Exp 2 flips a follower at 0.70 rad and above
  // with body-rate damping and thrust-first allocation (measured, docs/DISCUSSION.md).
  static constexpr double kMaxTiltUnfixed = 0.65;
  // The roll/pitch PD of the paper's experiments (torque = I (kp e - kd w)), used as they are on
  // any vehicle whose torque authority can follow them (every vehicle of 1-4 kg flown so far).
  static constexpr double kNominalTiltMax = 0.35;  // rad
  static constexpr double kNominalKpAtt = 150;     // 1/s^2
  static constexpr double kNominalKdAtt = 22;      // 1/s
  struct Vehicle {
    double mass = 0;     // kg
    double gravity = 0;  // m/s^2, magnitude
    Vec3 inertia{};      // kg m^2, principal moments (body axes)
  };
  struct Output {
    std::array<double, Mixer::kRotors> ctrl{};  // N, rotor thrust commands
    double thrust = 0;                          // N, wanted collective thrust
    Vec3 torque{};                              // N m, wanted body torques
    double roll_ref = 0, pitch_ref = 0;         // rad, from eq. (9) after the tilt limit
    Mixer::Result mix;
  };

  // Throws std::invalid_argument on a non-positive mass, gravity, inertia or gain (ki_z, imax_z
  // may be 0), tilt_max outside [0, pi/2) (0: derived), a resolved tilt_max above kMaxTiltUnfixed
  // without both large-tilt fixes, or a singular allocation.
  PdCascade(const Gains& gains, const Vehicle& vehicle,
            const std::array<RotorGeometry, Mixer::kRotors>& rotors);

  // One control step of dt seconds (integrator update). No allocation.
  Output Update(const VehicleState& state, const Setpoint& setpoint, double dt);

  // The gains with tilt_max, kp_att and kd_att resolved. A 0 tilt_max is
  // AuthorityTiltLimit(alpha, kNominalTiltMax). A 0 kp_att / kd_att is the nominal value, scaled so
  // that the loop's attitude gain kp / kd stays within AuthorityAttitudeBandwidth(alpha,
  // tilt_max) (types.hpp) for the weaker tilt axis' angular authority alpha (rad/s^2, torque at
  // hover over inertia): kp by c^2, kd by c, c = min(1, that bandwidth / (150 / 22)), which
  // keeps the damping ratio. An explicit (non-zero) gain is kept as given. The Iris (alpha 60
  // rad/s^2) keeps 150 / 22 up to tilt_max 1.3 rad; Menagerie's Crazyflie (0.42 rad/s^2) at
  // 0.35 rad gets kp 3.8, kd 3.5.
  static Gains Resolve(const Gains& gains, double alpha);

  // Clears the altitude integrator.
  void Reset() { integral_z_ = 0; }

  const Mixer& mixer() const { return mixer_; }
  const Gains& gains() const { return gains_; }
  // The attitude gain kp / kd (1/s) without the torque-authority limit (the nominal or given
  // gains): the loop the outer loops were tuned against.
  double unlimited_att_bw() const { return unlimited_att_bw_; }
  double altitude_integral() const { return integral_z_; }  // m/s^2
  // What a step leaves for the next: the altitude integrator (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(integral_z_);
  }

 private:
  // The tilt limit on the references of eq. (9) (pd_cascade.cc).
  void LimitTilt(double* roll_ref, double* pitch_ref) const;

  Gains gains_;
  Vehicle vehicle_;
  Mixer mixer_;
  double unlimited_att_bw_ = 0;   // 1/s
  double cos_tilt_max_ = 1;       // cos(gains_.tilt_max): the floor of the thrust's tilt factor
  double tilt_max_sq_below_ = 0;  // tilt_max^2 (1 - 1e-9): below it the tilt limit is not hit
  double integral_z_ = 0;         // m/s^2, ki_z * integral of the altitude error
};

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_PD_CASCADE_HPP_
