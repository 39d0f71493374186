// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/attitude/mixer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace mjf::attitude {
namespace {

const char* const kAxes[] = {"thrust", "roll torque", "pitch torque", "yaw torque"};

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

// Refuses an axis no rotor acts on: "no roll authority: rotors 0-3 give no roll torque".
void RequireEveryAxis(const Eigen::Matrix4d& b) {
  const double scale = b.cwiseAbs().maxCoeff();
  for (int axis = 0; axis < 4; ++axis) {
    if (b.row(axis).cwiseAbs().maxCoeff() <= 1e-9 * scale) {
      throw std::invalid_argument(
          std::string("the rotor layout has no ") + (axis == 0 ? "thrust" : kAxes[axis]) +
          " authority: none of rotors 0-3 gives any " + kAxes[axis] +
          (axis == 0 ? "" : " (all on the axis through the centre of mass, or gears without it)") +
          ": check rotor site positions and gears");
    }
  }
}

// Says which axes and which rotors are dependent in a singular or ill-conditioned B: the left
// singular vector of the smallest singular value is a combination of wrench axes no rotor
// changes (c^T B ~ 0), the right one a combination of rotors that changes no axis (B v ~ 0).
std::string Dependence(const Eigen::JacobiSVD<Eigen::Matrix4d>& svd) {
  const Eigen::Vector4d c = svd.matrixU().col(3), v = svd.matrixV().col(3);
  std::vector<int> axes, rotors;
  for (int i = 0; i < 4; ++i) {
    if (std::abs(c[i]) > 0.05 * c.cwiseAbs().maxCoeff()) axes.push_back(i);
    if (std::abs(v[i]) > 0.05 * v.cwiseAbs().maxCoeff()) rotors.push_back(i);
  }
  std::string out;
  if (axes.size() == 2) {
    out = std::string(kAxes[axes[1]]) + " is proportional to " + kAxes[axes[0]] + " (" +
          kAxes[axes[1]] + " = " + Number(-c[axes[0]] / c[axes[1]]) + " x " + kAxes[axes[0]] +
          " for every rotor)";
  } else {
    out = "a combination of";
    for (int i : axes) out += std::string(" ") + kAxes[i] + " (" + Number(c[i]) + ")";
    out += " is the same for every rotor";
  }
  out += ";";
  for (int k : rotors) out += " rotor" + std::to_string(k) + " (" + Number(v[k]) + ")";
  return out + " in that proportion change nothing";
}

}  // namespace

Mixer::Mixer(const std::array<RotorGeometry, kRotors>& rotors) {
  for (int k = 0; k < kRotors; ++k) {
    const RotorGeometry& r = rotors[k];
    const Eigen::Vector3d pos(r.pos[0], r.pos[1], r.pos[2]);
    const Eigen::Vector3d force(r.gear[0], r.gear[1], r.gear[2]);
    const Eigen::Vector3d torque =
        pos.cross(force) + Eigen::Vector3d(r.gear[3], r.gear[4], r.gear[5]);
    allocation_.col(k) << force.z(), torque;  // thrust along body z, torque x, y, z
    if (!(r.ctrl_min < r.ctrl_max)) {
      throw std::invalid_argument("rotor " + std::to_string(k) + ": empty control range");
    }
    ctrl_min_[k] = r.ctrl_min;
    ctrl_max_[k] = r.ctrl_max;
  }
  RequireEveryAxis(allocation_);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(allocation_,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  condition_ = sv[3] > 0 ? sv[0] / sv[3] : INFINITY;
  if (!(condition_ < kMaxCondition)) {
    throw std::invalid_argument(
        "the rotor allocation matrix (thrust, torques vs rotor thrusts) is singular or "
        "ill-conditioned (condition number " +
        Number(condition_) + "): " + Dependence(svd) +
        "; check rotor site positions and gears (a yaw gear of the wrong sign, as in Menagerie's "
        "Skydio X2: docs/VEHICLES.md, \"Menagerie's Crazyflie 2 and Skydio X2\")");
  }
  inverse_ = allocation_.inverse();
}

// A rotor's room / delta is divided out only when it is below 1: s starts at 1 and only falls,
// so a quotient of at least 1 never lowers it, and room >= delta (room <= delta for a negative
// delta) says so exactly (a correctly rounded quotient of a value >= 1 is >= 1). Unsaturated,
// the usual case, this costs no division; the result is the same number either way.
double Mixer::MaxScale(const Eigen::Vector4d& base, const Eigen::Vector4d& delta) const {
  double s = 1;
  for (int k = 0; k < kRotors; ++k) {
    if (delta[k] > 0) {
      const double room = ctrl_max_[k] - base[k];
      if (!(room >= delta[k])) s = std::min(s, room / delta[k]);
    } else if (delta[k] < 0) {
      const double room = ctrl_min_[k] - base[k];
      if (!(room <= delta[k])) s = std::min(s, room / delta[k]);
    }
  }
  return std::max(s, 0.0);
}

double Mixer::TorqueAuthority(int axis, double thrust) const {
  const Eigen::Vector4d base = inverse_.col(0) * thrust;
  const Eigen::Vector4d per_newton_metre = inverse_.col(1 + axis);
  double out = INFINITY;
  for (const double sign : {1.0, -1.0}) {
    for (int k = 0; k < kRotors; ++k) {
      const double d = sign * per_newton_metre[k];
      if (d > 0) out = std::min(out, (ctrl_max_[k] - base[k]) / d);
      if (d < 0) out = std::min(out, (ctrl_min_[k] - base[k]) / d);
    }
  }
  return std::max(out, 0.0);
}

bool Mixer::ThrustInterval(const Eigen::Vector4d& extra, double* lo, double* hi) const {
  *lo = -INFINITY;
  *hi = INFINITY;
  for (int k = 0; k < kRotors; ++k) {
    const double c = inverse_(k, 0);  // rotor k's share of one newton of collective
    const double below = ctrl_min_[k] - extra[k], above = ctrl_max_[k] - extra[k];
    if (c > 0) {
      *lo = std::max(*lo, below / c);
      *hi = std::min(*hi, above / c);
    } else if (c < 0) {
      *lo = std::max(*lo, above / c);
      *hi = std::min(*hi, below / c);
    } else if (below > 0 || above < 0) {
      return false;
    }
  }
  return *lo <= *hi;
}

Mixer::Result Mixer::MixRollPitchFirst(const Wrench& wanted) const {
  Result result;
  const Eigen::Vector4d u_roll_pitch = inverse_.col(1) * wanted[1] + inverse_.col(2) * wanted[2];
  const Eigen::Vector4d u_yaw = inverse_.col(3) * wanted[3];
  double lo = 0, hi = 0;
  // Largest fraction s of the roll/pitch torque that fits at some collective t. With every rotor
  // adding to the collective (c_k = inverse_(k, 0) > 0) rotor k allows
  // t in [(min_k - s r_k) / c_k, (max_k - s r_k) / c_k]; the intervals meet iff for every pair
  // (k, j): s (r_j / c_j - r_k / c_k) <= max_j / c_j - min_k / c_k. Closed form, no allocation.
  double s = 1;
  if (!ThrustInterval(u_roll_pitch, &lo, &hi)) {
    bool all_positive = true;
    for (int k = 0; k < kRotors; ++k) all_positive &= inverse_(k, 0) > 0;
    if (all_positive) {
      for (int k = 0; k < kRotors; ++k) {
        for (int j = 0; j < kRotors; ++j) {
          const double a = u_roll_pitch[j] / inverse_(j, 0) - u_roll_pitch[k] / inverse_(k, 0);
          if (a > 0) {
            s = std::min(s, (ctrl_max_[j] / inverse_(j, 0) - ctrl_min_[k] / inverse_(k, 0)) / a);
          }
        }
      }
      s = std::max(s, 0.0);
    } else {
      // Other geometries: feasibility is monotone in s (a convex set containing s = 0): bisect.
      double feasible = 0, infeasible = 1;
      for (int i = 0; i < 50; ++i) {
        const double mid = 0.5 * (feasible + infeasible);
        (ThrustInterval(mid * u_roll_pitch, &lo, &hi) ? feasible : infeasible) = mid;
      }
      s = feasible;
    }
  }
  result.roll_pitch_scale = s;
  if (s < 1) ThrustInterval(s * u_roll_pitch, &lo, &hi);  // else [lo, hi] is already for s = 1
  result.thrust = std::clamp(wanted[0], lo, hi);  // the collective closest to the wanted one
  result.thrust_saturated = result.thrust != wanted[0];
  Eigen::Vector4d u = inverse_.col(0) * result.thrust + s * u_roll_pitch;
  result.yaw_scale = MaxScale(u, u_yaw);
  u += result.yaw_scale * u_yaw;
  for (int k = 0; k < kRotors; ++k) result.ctrl[k] = std::clamp(u[k], ctrl_min_[k], ctrl_max_[k]);
  return result;
}

Mixer::Result Mixer::Mix(const Wrench& wanted, Priority priority) const {
  if (priority == Priority::kRollPitchFirst) return MixRollPitchFirst(wanted);
  Result result;
  // Split u = B^-1 w into the parts of thrust, roll/pitch torque and yaw torque.
  const Eigen::Vector4d u_thrust = inverse_.col(0) * wanted[0];
  const Eigen::Vector4d u_roll_pitch = inverse_.col(1) * wanted[1] + inverse_.col(2) * wanted[2];
  const Eigen::Vector4d u_yaw = inverse_.col(3) * wanted[3];

  const double thrust_scale = MaxScale(Eigen::Vector4d::Zero(), u_thrust);
  result.thrust_saturated = thrust_scale < 1;
  result.thrust = thrust_scale * wanted[0];
  Eigen::Vector4d u = thrust_scale * u_thrust;
  result.roll_pitch_scale = MaxScale(u, u_roll_pitch);
  u += result.roll_pitch_scale * u_roll_pitch;
  result.yaw_scale = MaxScale(u, u_yaw);
  u += result.yaw_scale * u_yaw;
  for (int k = 0; k < kRotors; ++k) result.ctrl[k] = std::clamp(u[k], ctrl_min_[k], ctrl_max_[k]);
  return result;
}

}  // namespace mjf::attitude
