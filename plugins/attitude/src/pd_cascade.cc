// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/attitude/pd_cascade.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mjf::attitude {

PdCascade::Gains PdCascade::Resolve(const Gains& gains, double alpha) {
  Gains g = gains;
  if (g.tilt_max == 0) g.tilt_max = AuthorityTiltLimit(alpha, kNominalTiltMax);
  const double limit = AuthorityAttitudeBandwidth(alpha, g.tilt_max);
  // The PD torque I (kp e - kd w) = I kd ((kp / kd) e - w) is a rate loop of gain kd under an
  // attitude loop of gain kp / kd (1/s): the criterion bounds the latter.
  const double c = std::min(1.0, limit / (kNominalKpAtt / kNominalKdAtt));
  if (g.kp_att == 0) g.kp_att = c < 1 ? kNominalKpAtt * c * c : kNominalKpAtt;
  if (g.kd_att == 0) g.kd_att = c < 1 ? kNominalKdAtt * c : kNominalKdAtt;
  return g;
}

namespace {

// The weaker tilt axis' angular authority at hover (rad/s^2).
double TiltAuthority(const Mixer& mixer, const PdCascade::Vehicle& vehicle) {
  const double hover = vehicle.mass * vehicle.gravity;
  return std::min(mixer.TorqueAuthority(0, hover) / vehicle.inertia[0],
                  mixer.TorqueAuthority(1, hover) / vehicle.inertia[1]);
}

}  // namespace

PdCascade::PdCascade(const Gains& gains, const Vehicle& vehicle,
                     const std::array<RotorGeometry, Mixer::kRotors>& rotors)
    : gains_(gains), vehicle_(vehicle), mixer_(rotors) {
  RequirePositive(vehicle.mass, "vehicle mass");
  RequirePositive(vehicle.gravity, "gravity");
  for (double i : vehicle.inertia) RequirePositive(i, "vehicle inertia");
  if (!(gains.tilt_max >= 0 && gains.tilt_max < M_PI / 2)) {
    throw std::invalid_argument("tilt_max must be in [0, pi/2) rad, 0: derived (got " +
                                std::to_string(gains.tilt_max) + ")");
  }
  RequireNonNegative(gains.kp_att, "kp_att");
  RequireNonNegative(gains.kd_att, "kd_att");
  gains_ = Resolve(gains, TiltAuthority(mixer_, vehicle));
  const bool fixed =
      gains.euler_rate_damping && gains.allocation == Mixer::Priority::kRollPitchFirst;
  if (gains_.tilt_max > kMaxTiltUnfixed && !fixed) {
    throw std::invalid_argument(
        "tilt_max " + std::to_string(gains_.tilt_max) + " rad is above " +
        std::to_string(kMaxTiltUnfixed) +
        " rad: with body-rate damping and thrust-first allocation a follower flips there (Exp 2 "
        "flips at 0.70 rad and above; docs/DISCUSSION.md). Set damping = \"euler_rates\" and "
        "allocation = \"roll_pitch_first\", or use the geometric plugin");
  }
  // Constants of Update, once: libm calls are not merged across steps (-fmath-errno keeps GCC
  // from treating cos as pure), and the bits are those Update computed each step.
  cos_tilt_max_ = std::cos(gains_.tilt_max);
  tilt_max_sq_below_ = gains_.tilt_max * gains_.tilt_max * (1 - 1e-9);
  const Gains unlimited = Resolve(gains, INFINITY);
  unlimited_att_bw_ = unlimited.kp_att / unlimited.kd_att;
  RequirePositive(gains.kp_yaw, "kp_yaw");
  RequirePositive(gains.kd_yaw, "kd_yaw");
  RequirePositive(gains.kp_z, "kp_z");
  RequirePositive(gains.kd_z, "kd_z");
  RequireNonNegative(gains.ki_z, "ki_z");
  RequireNonNegative(gains.imax_z, "imax_z");
}

// Keeps the direction of the horizontal command: (roll_ref, pitch_ref) scaled onto tilt_max
// when their norm hypot(roll_ref, pitch_ref) is above it. The norm is needed only when it may
// exceed tilt_max: a sum of squares below tilt_max^2 (1 - 1e-9) puts the true norm below
// tilt_max by about 5e-10 relative, far more than the few ulps by which the sum and hypot can
// err, so hypot would return less than tilt_max and nothing would change. Below the limit (most
// steps of level flight) the libm call is skipped; the references are the same bits either way.
void PdCascade::LimitTilt(double* roll_ref, double* pitch_ref) const {
  if (*roll_ref * *roll_ref + *pitch_ref * *pitch_ref < tilt_max_sq_below_) return;
  const double tilt = std::hypot(*roll_ref, *pitch_ref);
  if (tilt > gains_.tilt_max) {
    *roll_ref *= gains_.tilt_max / tilt;
    *pitch_ref *= gains_.tilt_max / tilt;
  }
}

PdCascade::Output PdCascade::Update(const VehicleState& state, const Setpoint& setpoint,
                                    double dt) {
  Output out;
  const double g = vehicle_.gravity;
  const Vec3 euler = EulerZYX(state.quat);
  const double roll = euler[0], pitch = euler[1], yaw = euler[2];
  const double cos_yaw = std::cos(yaw), sin_yaw = std::sin(yaw);

  // Eq. (9) inverted for the references, with the measured yaw:
  //   [ax; ay] = g [cos psi, sin psi; sin psi, -cos psi] [theta; phi], the matrix is its own
  //   inverse, so theta = (ax cos psi + ay sin psi) / g, phi = (ax sin psi - ay cos psi) / g.
  double pitch_ref = (setpoint.acc[0] * cos_yaw + setpoint.acc[1] * sin_yaw) / g;  // eq. (9)
  double roll_ref = (setpoint.acc[0] * sin_yaw - setpoint.acc[1] * cos_yaw) / g;   // eq. (9)
  LimitTilt(&roll_ref, &pitch_ref);
  out.roll_ref = roll_ref;
  out.pitch_ref = pitch_ref;

  // PD attitude (Fig. 2 inner loop). By default the body rates stand for the Euler rates, which
  // holds near hover only: tilted by theta and yawing at r, the roll angle also moves at
  // r cos(phi) tan(theta), which body-rate damping does not see. euler_rate_damping damps the
  // true ZYX Euler rates: phi' = p + (q sin phi + r cos phi) tan theta,
  // theta' = q cos phi - r sin phi.
  const Vec3& rate = state.gyro;
  double roll_rate = rate[0], pitch_rate = rate[1];
  if (gains_.euler_rate_damping) {
    roll_rate = rate[0] + (rate[1] * std::sin(roll) + rate[2] * std::cos(roll)) * std::tan(pitch);
    pitch_rate = rate[1] * std::cos(roll) - rate[2] * std::sin(roll);
  }
  out.torque[0] =
      vehicle_.inertia[0] * (gains_.kp_att * (roll_ref - roll) - gains_.kd_att * roll_rate);
  out.torque[1] =
      vehicle_.inertia[1] * (gains_.kp_att * (pitch_ref - pitch) - gains_.kd_att * pitch_rate);
  out.torque[2] =
      vehicle_.inertia[2] * (gains_.kp_yaw * WrapPi(setpoint.yaw - yaw) - gains_.kd_yaw * rate[2]);

  // PID altitude: vertical acceleration wanted, then the thrust that gives it at this tilt.
  const double z_error = setpoint.pos[2] - state.pos[2];
  const double az = setpoint.acc[2] + gains_.kp_z * z_error +
                    gains_.kd_z * (setpoint.vel[2] - state.vel[2]) + integral_z_;
  const double tilt_cos = std::max(std::cos(roll) * std::cos(pitch), cos_tilt_max_);
  out.thrust = std::max(0.0, vehicle_.mass * (g + az) / tilt_cos);

  out.mix = mixer_.Mix(Wrench(out.thrust, out.torque[0], out.torque[1], out.torque[2]),
                       gains_.allocation);
  out.ctrl = out.mix.ctrl;

  // Anti-windup: clamp, and do not integrate further into a saturated thrust.
  const bool pushing_saturation =
      (out.mix.thrust_saturated && out.mix.thrust < out.thrust && z_error > 0) ||
      ((out.thrust <= 0 || out.mix.thrust > out.thrust) && z_error < 0);
  if (!pushing_saturation) {
    integral_z_ =
        std::clamp(integral_z_ + gains_.ki_z * z_error * dt, -gains_.imax_z, gains_.imax_z);
  }
  return out;
}

}  // namespace mjf::attitude
