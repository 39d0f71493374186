// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/control/torque_authority.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "actuator_matrix.hpp"

namespace mjf::runner {
namespace {

constexpr int kActuators = 4;
const char* const kAxisNames[] = {"roll", "pitch", "yaw"};

// Largest s >= 0 with base + s * d and base - s * d inside [lo, hi] (infinite without limits).
double LargestSymmetricStep(const Eigen::Vector4d& base, const Eigen::Vector4d& d,
                            const Eigen::Vector4d& lo, const Eigen::Vector4d& hi) {
  double s = INFINITY;
  for (int k = 0; k < kActuators; ++k) {
    const double a = std::abs(d[k]);
    if (a == 0) continue;
    // +-s d[k] must fit on both sides of base[k].
    s = std::min(s, std::min(hi[k] - base[k], base[k] - lo[k]) / a);
  }
  return std::max(s, 0.0);
}

}  // namespace

TorqueAuthority ComputeTorqueAuthority(const mjfVehicleInfo& info) {
  TorqueAuthority out;
  if (info.n_actuators != kActuators || !info.actuators) {
    out.why = fmt::format("{} actuators, not four rotors or a thrust and three moments",
                          info.n_actuators);
    return out;
  }
  const ActuatorMatrix m = ActuatorMatrixOf(info);
  const Eigen::Matrix4d& b = m.b;
  const Eigen::Vector4d &lo = m.lo, &hi = m.hi;
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(b);
  if (!lu.isInvertible()) {
    out.why = "the actuators' allocation (thrust, torques) is singular";
    return out;
  }
  const Eigen::Matrix4d inv = lu.inverse();
  const double weight = info.mass * info.gravity;
  const Eigen::Vector4d hover = inv.col(0) * weight;
  // A vehicle whose actuators cannot hold its weight has no margin to give torques from: said
  // as such, rather than as an authority of 0 that asks for an infinitely wider range.
  for (int k = 0; k < kActuators; ++k) {
    if (hover[k] < lo[k] || hover[k] > hi[k]) {
      out.cannot_hover = true;
      out.why = fmt::format(
          "the actuators cannot hold its weight ({:.3g} kg x {:.3g} m/s^2 = {:.3g} N): hovering "
          "takes actuator {} to {:.3g}, outside its ctrlrange [{:.3g}, {:.3g}]",
          info.mass, info.gravity, weight, k, hover[k], lo[k], hi[k]);
      return out;
    }
  }
  out.known = true;
  for (int axis = 0; axis < 3; ++axis) {
    out.inertia[axis] = info.inertia[axis];
    out.torque[axis] = LargestSymmetricStep(hover, inv.col(1 + axis), lo, hi);
    out.accel[axis] = info.inertia[axis] > 0 ? out.torque[axis] / info.inertia[axis] : 0.0;
  }
  return out;
}

double DemandedTiltAcceleration(double att_bw, double tilt_max) {
  return att_bw * att_bw * tilt_max;
}

std::string AuthorityText(const TorqueAuthority& a) {
  if (!a.known) return "torque authority: not computed (" + a.why + ")";
  std::string text = "torque authority at hover:";
  for (int axis = 0; axis < 3; ++axis) {
    text += fmt::format("{} {} {:.3g} rad/s^2 ({:.3g} N m / {:.3g} kg m^2)", axis ? "," : "",
                        kAxisNames[axis], a.accel[axis], a.torque[axis], a.inertia[axis]);
  }
  return text;
}

// The slowest attitude loop the stock outer loops sit on (rad/s) and the smallest tilt limit
// that leaves the formation acceleration for its reaching phase (rad, g tan 0.03 = 0.29 m/s^2):
// both measured on Menagerie's cf2 (docs/VEHICLES.md; the attitude plugins' kMinAttitudeBandwidth).
constexpr double kMinOuterLoopBandwidth = 3.0;
constexpr double kMinFormationTilt = 0.03;

namespace {

// The warning for one axis short of authority, with the ways out: a wider range, the tilt limit
// this authority follows at this bandwidth, and the bandwidth it follows at this tilt limit.
std::string ShortAxisWarning(const TorqueAuthority& a, const AttitudeDemand& d,
                             const std::string& vehicle, int axis, bool alike) {
  const double bw = d.Reference();
  const double demand = DemandedTiltAcceleration(bw, d.tilt_max);
  const bool lowered = d.att_bw_unlimited > d.att_bw;
  const double alpha = a.accel[axis];
  std::string text = fmt::format(
      "{}: {} torque authority {:.3g} rad/s^2 ({:.3g} N m / {:.3g} kg m^2) is below the {:.3g} "
      "rad/s^2 the attitude loop asks for (att_bw^2 x tilt_max = {:.3g}^2 x {:.3g}): the "
      "vehicle cannot follow the demanded tilt",
      vehicle, alike ? "roll and pitch" : kAxisNames[axis], alpha, a.torque[axis], a.inertia[axis],
      demand, bw, d.tilt_max);
  if (lowered) {
    text += fmt::format(
        "; the attitude plugin lowered its default att_bw to {:.3g} rad/s to stay within it, "
        "and the formation and guidance loops above, tuned for {:.3g} rad/s, may outrun it",
        d.att_bw, bw);
  }
  // What happens: a loop the plugin slowed to the authority but kept at or above the slowest
  // one the stock outer loops sit on flies (the published cf2: att_bw 3.0 rad/s, no event, a
  // less precise formation); a slower one, or a loop the authority cannot follow, rocks or flips.
  if (lowered && d.att_bw >= kMinOuterLoopBandwidth - 1e-9) {
    text += fmt::format(
        ". At {:.3g} rad/s it is still fast enough for the stock outer loops (from about {:g} "
        "rad/s, docs/VEHICLES.md): expect a less precise formation, not flips. For the loop the "
        "experiment was tuned with, raise the moment ctrlrange (or the rotors' range and arms) "
        "{:.3g}x",
        d.att_bw, kMinOuterLoopBandwidth, demand / alpha);
  } else {
    text += fmt::format(
        ". Expect rocking or flips: raise the moment ctrlrange (or the rotors' range and arms) "
        "{:.3g}x",
        demand / alpha);
  }
  // The tilt limit this authority follows at this bandwidth, advised only where the formation
  // keeps enough horizontal acceleration (g tan tilt) for its reaching phase.
  const double tilt = alpha / (bw * bw);
  if (tilt >= kMinFormationTilt) {
    text += fmt::format(", or lower tilt_max to {:.3g} rad", tilt);
  } else {
    text += fmt::format(
        " (no tilt limit helps at {:.3g} rad/s: the one this authority follows, {:.3g} rad, "
        "leaves the formation too little acceleration, below about {:g} rad)",
        bw, tilt, kMinFormationTilt);
  }
  if (!lowered) {
    text += fmt::format(", or the attitude gains to att_bw {:.3g} rad/s",
                        std::sqrt(alpha / d.tilt_max));
  }
  return text;
}

}  // namespace

std::vector<std::string> AuthorityWarnings(const TorqueAuthority& a, const AttitudeDemand& d,
                                           const std::string& vehicle) {
  std::vector<std::string> out;
  if (a.cannot_hover) {
    out.push_back(vehicle + ": " + a.why +
                  ": it cannot hover, so it falls; lower the model's mass or raise the "
                  "actuators' ctrlrange (or the rotors' gear)");
    return out;
  }
  const double bw = d.Reference();
  const double demand = DemandedTiltAcceleration(bw, d.tilt_max);
  if (!a.known || !std::isfinite(demand) || !(demand > 0)) return out;
  std::vector<int> short_axes;
  for (int axis = 0; axis < 2; ++axis) {
    if (a.accel[axis] < demand) short_axes.push_back(axis);
  }
  // Roll and pitch alike (a symmetric vehicle, e.g. a thrust-and-moment one): one warning.
  const bool alike = short_axes.size() == 2 && a.accel[0] == a.accel[1] &&
                     a.torque[0] == a.torque[1] && a.inertia[0] == a.inertia[1];
  if (alike) short_axes.pop_back();
  for (const int axis : short_axes) {
    out.push_back(ShortAxisWarning(a, d, vehicle, axis, alike));
  }
  return out;
}

}  // namespace mjf::runner
