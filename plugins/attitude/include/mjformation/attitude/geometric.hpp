// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// A quadrotor inner loop on the full nonlinear model, PX4 multicopter structure:
//   acceleration setpoint -> thrust vector F = m (a + g e3) (no small-angle model), with a tilt
//   limit that keeps altitude priority -> desired attitude (body z along F, heading from yaw) ->
//   quaternion attitude error, tilt first then yaw (no Euler angles, q and -q alike) -> body-rate
//   PI loop -> mixer that keeps roll/pitch, then thrust, and gives up yaw first.
//
// Thrust direction and magnitude follow T. Lee, M. Leok, N. H. McClamroch, "Geometric tracking
// control of a quadrotor UAV on SE(3)", IEEE CDC 2010: b3d = F / |F| (their eq. (12) with the
// position terms replaced by the acceleration setpoint), collective f = F . R e3 (eq. (15)). The
// attitude error is the quaternion form (tilt-prioritised, as in D. Brescianini, M. Hehn,
// R. D'Andrea, "Nonlinear quadrocopter attitude control", ETH tech. report 2013) instead of
// Lee's vee map: its magnitude 2 sin(angle / 2) grows up to a 180 deg error, where Lee's
// sin(angle) vanishes.
//
// Gains left at 0 are derived from the vehicle (Derive()): the rate loop from the motor lag, the
// attitude and altitude loops from the rate loop, every loop normalised by the inertia and mass,
// so the same attribute values fly any quadrotor whose info the runner passes.
#ifndef MJFORMATION_ATTITUDE_GEOMETRIC_HPP_
#define MJFORMATION_ATTITUDE_GEOMETRIC_HPP_

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "mjformation/attitude/mixer.hpp"
#include "mjformation/attitude/types.hpp"

namespace mjf::attitude {

class Geometric {
 public:
  // Bandwidths in rad/s; 0 = derive from the vehicle (see Derive()).
  struct Gains {
    // rad, limit on the angle between F and the vertical; 0 = derived (Resolve): kNominalTiltMax
    // (PX4: 45 deg), lowered to the vehicle's torque authority (AuthorityTiltLimit, types.hpp).
    double tilt_max = 0;
    double rate_bw = 0;          // rad/s, roll/pitch/yaw rate loop crossover; 0: 0.5 / motor lag
    double att_bw = 0;           // rad/s, roll/pitch attitude loop gain; 0: rate_bw / 3
    double yaw_bw = 0;           // rad/s, yaw attitude loop gain; 0: att_bw / 2
    double z_bw = 0;             // rad/s, altitude loop natural frequency; 0: att_bw / 2.5
    double rate_ki = 0.1;        // rate integral zero as a fraction of rate_bw (0: no integral)
    double thrust_margin = 0.1;  // fraction of the total rotor thrust kept for torque
  };
  struct Vehicle {
    double mass = 0;          // kg
    double gravity = 0;       // m/s^2, magnitude
    Vec3 inertia{};           // kg m^2, principal moments (body axes)
    double motor_lag = 0;     // s, slowest rotor's first-order time constant (0: none)
    double timestep = 0.001;  // s, control period
  };
  // The loop gains actually used, in the units of the equations in Update().
  struct Derived {
    double k_rate = 0;                    // 1/s: angular acceleration per rad/s of rate error
    double ki_rate = 0;                   // 1/s^2: rate integral
    double imax_rate = 0;                 // rad/s^2: bound on the rate integral
    double k_att = 0;                     // 1/s: rate reference per rad of tilt error
    double k_yaw = 0;                     // 1/s: yaw rate reference per rad of yaw error
    double kp_z = 0, kd_z = 0, ki_z = 0;  // 1/s^2, 1/s, 1/s^3: altitude PID
    double imax_z = 0;                    // m/s^2
    double thrust_max = 0;  // N, collective the tilt limit may use (ranges minus the margin)
    double thrust_min = 0;  // N, least vertical thrust the setpoint may ask for
    double tan_tilt_max = 0;
  };
  struct Output {
    std::array<double, Mixer::kRotors> ctrl{};   // N, rotor thrust commands
    double thrust = 0;                           // N, wanted collective thrust
    Vec3 torque{};                               // N m, wanted body torques
    Vec3 force{};                                // N, world thrust vector after the tilt limit
    bool tilt_limited = false;                   // the horizontal force was cut
    std::array<double, 4> quat_ref{1, 0, 0, 0};  // w x y z, desired attitude
    Vec3 attitude_error{};                       // rad-like: 2 vec(q_err), body frame
    Vec3 rate_ref{};                             // rad/s, body frame
    Mixer::Result mix;
  };

  // Throws std::invalid_argument on a non-positive mass, gravity or inertia, a negative motor
  // lag, tilt_max outside (0, pi/2), a negative or non-finite gain, bandwidths that do not
  // separate (att_bw >= rate_bw / 2, z_bw >= att_bw, yaw_bw > att_bw), a rate loop faster than the
  // motors allow (rate_bw * motor_lag > 1), a singular allocation, or rotors too weak to hover.
  Geometric(const Gains& gains, const Vehicle& vehicle,
            const std::array<RotorGeometry, Mixer::kRotors>& rotors);

  // One control step of dt seconds. No allocation.
  Output Update(const VehicleState& state, const Setpoint& setpoint, double dt);

  void Reset();

  const Mixer& mixer() const { return mixer_; }
  const Gains& gains() const { return gains_; }
  const Derived& derived() const { return derived_; }
  // att_bw as it would be without the torque-authority cap (= gains().att_bw when the cap did
  // not bind or att_bw was given): the loop the outer loops were tuned against.
  double unlimited_att_bw() const { return unlimited_att_bw_; }
  double altitude_integral() const { return integral_z_; }  // m/s^2
  // What a step leaves for the next: the altitude and body-rate integrators (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(integral_z_, integral_rate_);
  }

  static constexpr double kNominalTiltMax = 0.78;  // rad
  // The resolved tilt limit and bandwidths (rad/s) for given gains and vehicle: 0 entries
  // replaced (tilt_max: AuthorityTiltLimit of the weaker tilt axis, types.hpp).
  static Gains Resolve(const Gains& gains, const Vehicle& vehicle,
                       const Vec3& angular_authority = {INFINITY, INFINITY, INFINITY});

 private:
  Gains gains_;  // resolved (no 0 bandwidth)
  Vehicle vehicle_;
  Mixer mixer_;
  Derived derived_;
  double unlimited_att_bw_ = 0;                              // rad/s
  double integral_z_ = 0;                                    // m/s^2
  Eigen::Vector3d integral_rate_ = Eigen::Vector3d::Zero();  // rad/s^2
};

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_GEOMETRIC_HPP_
