// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Plain inputs of the attitude controllers (no MuJoCo, no plugin ABI): what the vehicle's sensors
// say and what guidance or formation asks for. World frame z up, gravity -z (ENU-like).
#ifndef MJFORMATION_ATTITUDE_TYPES_HPP_
#define MJFORMATION_ATTITUDE_TYPES_HPP_

#include <array>

namespace mjf::attitude {

using Vec3 = std::array<double, 3>;

// The vehicle as its sensors report it.
struct VehicleState {
  Vec3 pos{};                              // m, world frame
  Vec3 vel{};                              // m/s, world frame
  std::array<double, 4> quat{1, 0, 0, 0};  // w x y z, body -> world
  Vec3 gyro{};                             // rad/s, body frame
};

// What the attitude loop is asked to do (the setpoint bus, mjfSetpoint).
struct Setpoint {
  Vec3 acc{};      // m/s^2, world: acc[0..1] horizontal command, acc[2] vertical feedforward
  Vec3 pos{};      // m, world: pos[2] is the altitude setpoint (x, y unused here)
  Vec3 vel{};      // m/s, world: vel[2] is the climb-rate reference (x, y unused here)
  double yaw = 0;  // rad
};

// Roll, pitch, yaw (rad) of a body -> world quaternion: mjf::EulerZYX (euler_zyx.hpp, the
// runner's too) as an Eigen vector.
Vec3 EulerZYX(const std::array<double, 4>& quat);

// Angle wrapped to [-pi, pi), rad.
double WrapPi(double angle);

// Parameter checks of the controllers' constructors: throw std::invalid_argument naming `what`
// and the value unless it is finite and > 0 (resp. >= 0).
void RequirePositive(double value, const char* what);
void RequireNonNegative(double value, const char* what);

// The fastest attitude loop (rad/s) whose response the torque authority can follow from a tilt
// error of tilt_max (rad), for an angular authority alpha (rad/s^2, torque over inertia):
// sqrt(alpha / tilt_max); infinity when alpha is infinite or not positive (nothing to cap).
//
// Why: an attitude loop of gain k (rate reference k e per rad of tilt error e, 1/s) returns the
// error along e(t) = e0 exp(-k t) once its faster rate loop follows; that motion needs the
// angular acceleration k^2 e(t), largest at the start, k^2 e0. The largest error the loop is
// asked to take out is about the tilt limit (a setpoint swung from level to tilt_max), so a
// vehicle with alpha >= k^2 tilt_max follows its own loop on every command; below it the
// deceleration the loop asks for is not there, the tilt overshoots, and the loop becomes a
// bang-bang one that rocks or flips. The rate loop's first instant asks more (k_rate k e0), but
// only for a fraction of its own time constant: saturating it delays the rate by about
// k e0 / alpha, which the criterion keeps below 1 / k. The runner warns with the same
// inequality (runner/control/src/torque_authority.cc, docs/VEHICLES.md).
double AuthorityAttitudeBandwidth(double alpha, double tilt_max);

// The slowest attitude loop (rad/s) the stock outer loops can sit on: the experiments' formation
// loop (k = [3, 1]) closes at about 3 rad/s, and an attitude loop below it is outrun. Measured on
// Menagerie's Crazyflie 2 (0.42 rad/s^2, docs/VEHICLES.md): loops of 2.4-3.2 rad/s (tilt limits
// 0.04-0.07 rad) fly the scaled Exp 2 without an event, 0.73 rad/s (tilt 0.78) flips every
// follower.
constexpr double kMinAttitudeBandwidth = 3.0;

// The default tilt limit (rad) of a vehicle of angular authority alpha (rad/s^2): the plugin's
// nominal limit, lowered to alpha / kMinAttitudeBandwidth^2 when the authority cannot follow a
// loop of kMinAttitudeBandwidth from the nominal tilt (the criterion above, solved for tilt_max).
// Smaller tilts ask less angular acceleration of the same loop, so a weak vehicle keeps a loop
// fast enough for its outer loops and gives up tilt (its largest horizontal acceleration, g tan
// tilt_max) instead. Every vehicle of 1-4 kg flown so far keeps the nominal limit (the Iris: 60.5
// rad/s^2 gives 6.7 rad); the cf2 gets 0.046 rad. Nothing is floored: below about 0.03 rad the
// formation lacks acceleration for its reaching phase (measured on the cf2), which the runner's
// torque-authority warning then reports.
double AuthorityTiltLimit(double alpha, double nominal_tilt);

}  // namespace mjf::attitude

#endif  // MJFORMATION_ATTITUDE_TYPES_HPP_
