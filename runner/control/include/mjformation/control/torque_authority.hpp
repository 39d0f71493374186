// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The torque-authority check (docs/VEHICLES.md, "Torque authority"): how fast each body axis of
// a vehicle can be accelerated at hover, from the actuator info the attitude plugin receives
// (gears, sites, control ranges) and the inertia, and whether that follows what the attitude
// loop and its tilt limit ask for. Plain arrays, no MuJoCo.
#ifndef MJFORMATION_CONTROL_TORQUE_AUTHORITY_HPP_
#define MJFORMATION_CONTROL_TORQUE_AUTHORITY_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <string>
#include <vector>

namespace mjf::runner {

struct TorqueAuthority {
  bool known = false;         // false: not a four-actuator vehicle with body torques (why says so)
  bool cannot_hover = false;  // the actuators cannot hold m g within their ctrlrange (why)
  std::string why;
  std::array<double, 3> torque{};   // N m, largest torque about body x, y, z (either sign)
  std::array<double, 3> inertia{};  // kg m^2
  std::array<double, 3> accel{};    // rad/s^2, torque / inertia
};

// Each axis' largest torque, in either direction, that the four actuators give while they hold
// the hover thrust (m g along body z) and no torque about the other axes, over the inertia.
// Rotor layouts: the allocation B (column k: actuator k's body-z force and torque, site x force
// plus its gear's torque) is inverted, u = B^-1 (m g, tau e_axis), and tau is the largest value
// that keeps every u within its ctrlrange. Thrust and moments: B is diagonal, so this is the
// moment actuator's range times |gear| (hover takes nothing from it).
TorqueAuthority ComputeTorqueAuthority(const mjfVehicleInfo& info);

// What the attitude loop asks for to follow its own response from a tilt error of tilt_max:
// att_bw^2 tilt_max (rad/s^2), att_bw the loop's rate reference per rad of tilt error (1/s).
// The derivation is at AuthorityAttitudeBandwidth (plugins/attitude/.../types.hpp), which the
// stock plugins use to keep their default gains within it.
double DemandedTiltAcceleration(double att_bw, double tilt_max);

// "torque authority at hover: roll 102 rad/s^2 (2.98 N m / 0.0291 kg m^2), pitch ..., yaw ..."
std::string AuthorityText(const TorqueAuthority& authority);

// What the attitude plugin says of its loop (its report(): att_bw, att_bw_unlimited, tilt_max).
struct AttitudeDemand {
  double att_bw = 0;            // 1/s, the attitude gain it flies with
  double att_bw_unlimited = 0;  // 1/s, the gain before its own torque-authority limit (0: same)
  double tilt_max = 0;          // rad
  // The loop the experiment was tuned with: the unlimited gain when the plugin lowered it.
  double Reference() const { return att_bw_unlimited > att_bw ? att_bw_unlimited : att_bw; }
};

// One warning per tilt axis (roll, pitch; one for both when they are alike) whose authority is
// below what the reference loop asks for (DemandedTiltAcceleration(demand.Reference(), tilt_max)),
// naming the vehicle, the axis, both figures and what to do; empty when it suffices (or is unknown,
// or the demand is not finite and positive). Judged against the unlimited loop, because a plugin
// that slowed its loop to the authority (the stock ones do) leaves the formation and guidance loops
// above it as fast as before: they may outrun it. Yaw is listed but not judged: no tilt limit
// bounds its error and the stock plugins give it up first.
std::vector<std::string> AuthorityWarnings(const TorqueAuthority& authority,
                                           const AttitudeDemand& demand,
                                           const std::string& vehicle);

}  // namespace mjf::runner

#endif  // MJFORMATION_CONTROL_TORQUE_AUTHORITY_HPP_
