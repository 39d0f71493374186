// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/attitude/geometric.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace mjf::attitude {
namespace {

// Rate loop crossover when the vehicle reports no motor lag: the sampling alone limits it.
constexpr double kRateBwPerSampleRate = 0.05;  // rad/s per Hz of control rate

}  // namespace

Geometric::Gains Geometric::Resolve(const Gains& gains, const Vehicle& vehicle,
                                    const Vec3& angular_authority) {
  Gains g = gains;
  if (g.tilt_max == 0) {
    g.tilt_max =
        AuthorityTiltLimit(std::min(angular_authority[0], angular_authority[1]), kNominalTiltMax);
  }
  // Rate loop: plant 1/s (angular acceleration -> rate) behind the motor lag tau plus about two
  // control periods of sampling delay; crossover at 0.9 / tau_eff leaves 48 deg of phase margin
  // (90 deg - atan(0.9)), the usual target for an inner rate loop. A slower rate loop (0.5 /
  // tau_eff, 63 deg, tried first) doubles the rocking of Exp 2 (docs/DISCUSSION.md): the formation
  // loop above it is sensitive to every bit of actuation lag.
  if (g.rate_bw == 0) {
    g.rate_bw = vehicle.motor_lag > 0 ? 0.9 / (vehicle.motor_lag + 2 * vehicle.timestep)
                                      : kRateBwPerSampleRate / vehicle.timestep;
    // Torque authority (AuthorityAttitudeBandwidth, types.hpp): the attitude loop att_bw =
    // rate_bw / 4 must find the angular acceleration att_bw^2 tilt_max to follow its own
    // response from a tilt error of tilt_max on the weaker tilt axis (alpha: torque at hover /
    // inertia), so rate_bw <= 4 sqrt(alpha / tilt_max). The lag bound decides for rotor
    // vehicles of 1-4 kg (the Iris: 33.3 rad/s, cap 35.2 at tilt_max 0.78), the cap for
    // weak-torque vehicles such as Menagerie's Crazyflie (1e-5 N m on 2.4e-5 kg m^2: 2.9 rad/s
    // instead of 50), which flip when every correction saturates the torque. A lower tilt_max
    // raises the cap: smaller tilts can be followed faster. Yaw is left out: its loop runs at
    // att_bw / 2, its setpoint does not jump by a tilt limit, and the mixer gives yaw up first.
    const double alpha = std::min(angular_authority[0], angular_authority[1]);
    g.rate_bw = std::min(g.rate_bw, 4 * AuthorityAttitudeBandwidth(alpha, g.tilt_max));
  }
  // Cascade separation: the attitude loop a factor 4 below the rate loop, yaw and altitude a
  // further 2 and 2.5 below.
  if (g.att_bw == 0) g.att_bw = g.rate_bw / 4;
  if (g.yaw_bw == 0) g.yaw_bw = g.att_bw / 2;
  if (g.z_bw == 0) g.z_bw = g.att_bw / 2.5;
  return g;
}

namespace {

// The gains as given (before 0 bandwidths are resolved) and the vehicle.
void CheckGiven(const Geometric::Gains& gains, const Geometric::Vehicle& vehicle) {
  RequirePositive(vehicle.mass, "vehicle mass");
  RequirePositive(vehicle.gravity, "gravity");
  for (double i : vehicle.inertia) RequirePositive(i, "vehicle inertia");
  RequireNonNegative(vehicle.motor_lag, "motor time constant");
  RequirePositive(vehicle.timestep, "timestep");
  if (!(gains.tilt_max >= 0 && gains.tilt_max < M_PI / 2)) {
    throw std::invalid_argument("tilt_max must be in [0, pi/2) rad, 0: derived (got " +
                                std::to_string(gains.tilt_max) + ")");
  }
  for (const auto& [value, name] :
       {std::pair{gains.rate_bw, "rate_bw"}, std::pair{gains.att_bw, "att_bw"},
        std::pair{gains.yaw_bw, "yaw_bw"}, std::pair{gains.z_bw, "z_bw"},
        std::pair{gains.rate_ki, "rate_ki"}}) {
    RequireNonNegative(value, name);
  }
  if (!(gains.thrust_margin >= 0 && gains.thrust_margin < 0.5)) {
    throw std::invalid_argument("thrust_margin must be in [0, 0.5) (got " +
                                std::to_string(gains.thrust_margin) + ")");
  }
  if (!(gains.rate_ki <= 0.5)) {
    throw std::invalid_argument(
        "rate_ki must be <= 0.5: an integral zero above half the rate "
        "bandwidth eats the phase margin (got " +
        std::to_string(gains.rate_ki) + ")");
  }
}

// The loop separation the resolved bandwidths g must keep.
void CheckResolved(const Geometric::Gains& g, const Geometric::Vehicle& vehicle) {
  if (vehicle.motor_lag > 0 && g.rate_bw * vehicle.motor_lag > 1) {
    throw std::invalid_argument(
        "rate_bw " + std::to_string(g.rate_bw) + " rad/s is beyond the motors (time constant " +
        std::to_string(vehicle.motor_lag) + " s): rate_bw * tau must be <= 1 (phase margin)");
  }
  if (!(g.att_bw <= g.rate_bw / 2)) {
    throw std::invalid_argument("att_bw must be <= rate_bw / 2 (cascade separation; got att_bw " +
                                std::to_string(g.att_bw) + ", rate_bw " +
                                std::to_string(g.rate_bw) + ")");
  }
  if (!(g.yaw_bw <= g.att_bw)) {
    throw std::invalid_argument("yaw_bw must be <= att_bw (got " + std::to_string(g.yaw_bw) + ")");
  }
  if (!(g.z_bw < g.att_bw)) {
    throw std::invalid_argument(
        "z_bw must be < att_bw: the altitude loop acts through the "
        "attitude loop (got z_bw " +
        std::to_string(g.z_bw) + ", att_bw " + std::to_string(g.att_bw) + ")");
  }
}

// The loop gains from the resolved bandwidths g; refuses rotors too weak to hover.
Geometric::Derived Derive(const Geometric::Gains& g, const Geometric::Vehicle& vehicle,
                          const Mixer& mixer,
                          const std::array<RotorGeometry, Mixer::kRotors>& rotors) {
  Geometric::Derived d;
  const double wr = g.rate_bw;
  const double tau = vehicle.motor_lag + 2 * vehicle.timestep;
  // |k / (j w (1 + j w tau))| = 1 at w = rate_bw.
  d.k_rate = wr * std::sqrt(1 + wr * wr * tau * tau);
  d.ki_rate = d.k_rate * g.rate_ki * wr;  // PI zero at rate_ki * rate_bw
  d.imax_rate = 0.2 * d.k_rate;           // as much as 0.2 rad/s of rate error
  d.k_att = g.att_bw;                     // rate_ref = k_att * error: crossover att_bw
  d.k_yaw = g.yaw_bw;
  const double wz = g.z_bw;  // altitude: s^2 + 2 wz s + wz^2, slow integral
  d.kp_z = wz * wz;
  d.kd_z = 2 * wz;
  d.ki_z = wz * wz * wz / 10;
  d.imax_z = 0.2 * vehicle.gravity;
  const Eigen::Vector4d all_max(rotors[0].ctrl_max, rotors[1].ctrl_max, rotors[2].ctrl_max,
                                rotors[3].ctrl_max);
  d.thrust_max = (1 - g.thrust_margin) * mixer.allocation().row(0).dot(all_max);
  d.thrust_min = 0.1 * vehicle.mass * vehicle.gravity;
  d.tan_tilt_max = std::tan(g.tilt_max);
  if (!(d.thrust_max > 1.05 * vehicle.mass * vehicle.gravity)) {
    throw std::invalid_argument("the rotors give at most " + std::to_string(d.thrust_max) +
                                " N of usable collective thrust, less than 1.05 x the weight " +
                                std::to_string(vehicle.mass * vehicle.gravity) +
                                " N: the vehicle cannot hover");
  }
  return d;
}

// Thrust vector F = m (a + g e3) for the vertical acceleration az, with altitude priority (see
// below); sets out->tilt_limited when the horizontal force is cut.
Eigen::Vector3d ThrustVector(const Geometric::Derived& k, double m, double g,
                             const Setpoint& setpoint, double az, Geometric::Output* out) {
  // Thrust vector F = m (a + g e3) (Lee et al. eq. (12)) with altitude priority: the vertical
  // part first (within [thrust_min, thrust_max]), then as much horizontal force as both the tilt
  // limit (|F_xy| <= F_z tan tilt_max) and the remaining thrust (|F| <= thrust_max) allow,
  // direction kept.
  const double fz = std::clamp(m * (g + az), k.thrust_min, k.thrust_max);
  Eigen::Vector2d fxy(m * setpoint.acc[0], m * setpoint.acc[1]);
  const double fxy_max =
      std::min(fz * k.tan_tilt_max, std::sqrt(k.thrust_max * k.thrust_max - fz * fz));
  const double fxy_norm = fxy.norm();
  if (fxy_norm > fxy_max) {
    fxy *= fxy_max / fxy_norm;
    out->tilt_limited = true;
  }
  return Eigen::Vector3d(fxy.x(), fxy.y(), fz);
}

// The attitude error (body frame) from the attitude q (rotation R) to the desired body z b3d
// and body x b1d (world); writes out->quat_ref.
Eigen::Vector3d AttitudeError(const Eigen::Quaterniond& q, const Eigen::Matrix3d& R,
                              const Eigen::Vector3d& b3d, const Eigen::Vector3d& b1d,
                              Geometric::Output* out) {
  // Attitude error, tilt first: q_tilt turns the body z onto b3d by the shortest arc (body frame,
  // axis perpendicular to body z), then q_yaw turns the tilted body about its z (= b3d) until its
  // x axis lies on b1d. Both are built from vectors and rotations, so q and -q give the same
  // error; 2 vec(q) with w >= 0 is 2 sin(angle / 2) along the axis: no Euler angles, no
  // singularity short of exactly 180 deg.
  const Eigen::Vector3d b3d_body = R.transpose() * b3d;
  Eigen::Quaterniond q_tilt;
  if (1 + b3d_body.z() > 1e-9) {
    q_tilt = Eigen::Quaterniond(1 + b3d_body.z(), -b3d_body.y(), b3d_body.x(), 0).normalized();
  } else {  // exactly upside down relative to F: any horizontal axis will do; take body x
    q_tilt = Eigen::Quaterniond(0, 1, 0, 0);
  }
  const Eigen::Quaterniond q_tilted = q * q_tilt;
  const Eigen::Vector3d x_tilted = q_tilted * Eigen::Vector3d::UnitX();  // world, normal to b3d
  const double half_yaw =  // half the angle from x_tilted to b1d about b3d, in [-pi/2, pi/2]
      0.5 * std::atan2(x_tilted.cross(b1d).dot(b3d), x_tilted.dot(b1d));
  const Eigen::Quaterniond q_yaw(std::cos(half_yaw), 0, 0, std::sin(half_yaw));
  const Eigen::Vector3d error(2 * q_tilt.x(), 2 * q_tilt.y(), 2 * q_yaw.z());
  const Eigen::Quaterniond q_ref = q_tilted * q_yaw;
  out->quat_ref = {q_ref.w(), q_ref.x(), q_ref.y(), q_ref.z()};
  if (out->quat_ref[0] < 0) {
    for (double& c : out->quat_ref) c = -c;
  }
  return error;
}

// The rate and altitude integrators after a step (wanted_fz: the vertical thrust the altitude
// loop asked for).
void Integrate(const Geometric::Derived& k, const Geometric::Output& out,
               const Eigen::Vector3d& rate_error, double wanted_fz, double z_error, double dt,
               Eigen::Vector3d* integral_rate, double* integral_z) {
  // Anti-windup: no integration on an axis the mixer cut, nor into a limited thrust.
  const bool rp_free = out.mix.roll_pitch_scale >= 1;
  const bool yaw_free = out.mix.yaw_scale >= 1 && rp_free;
  for (int i = 0; i < 3; ++i) {
    if (i < 2 ? rp_free : yaw_free) {
      (*integral_rate)[i] = std::clamp((*integral_rate)[i] + k.ki_rate * rate_error[i] * dt,
                                       -k.imax_rate, k.imax_rate);
    }
  }
  const bool at_max = wanted_fz > k.thrust_max || out.mix.thrust < out.thrust;
  const bool at_min = wanted_fz < k.thrust_min || out.mix.thrust > out.thrust;
  const bool pushing = (at_max && z_error > 0) || (at_min && z_error < 0);
  if (!pushing) {
    *integral_z = std::clamp(*integral_z + k.ki_z * z_error * dt, -k.imax_z, k.imax_z);
  }
}

}  // namespace

Geometric::Geometric(const Gains& gains, const Vehicle& vehicle,
                     const std::array<RotorGeometry, Mixer::kRotors>& rotors)
    : vehicle_(vehicle), mixer_(rotors) {
  CheckGiven(gains, vehicle);
  Vec3 authority;  // rad/s^2 per axis at hover thrust
  for (int i = 0; i < 3; ++i) {
    authority[i] = mixer_.TorqueAuthority(i, vehicle.mass * vehicle.gravity) / vehicle.inertia[i];
  }
  gains_ = Resolve(gains, vehicle, authority);
  unlimited_att_bw_ = Resolve(gains, vehicle).att_bw;
  CheckResolved(gains_, vehicle);
  derived_ = Derive(gains_, vehicle, mixer_, rotors);
}

void Geometric::Reset() {
  integral_z_ = 0;
  integral_rate_.setZero();
}

Geometric::Output Geometric::Update(const VehicleState& state, const Setpoint& setpoint,
                                    double dt) {
  Output out;
  const Derived& k = derived_;
  const double m = vehicle_.mass, g = vehicle_.gravity;
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(state.quat[0], state.quat[1], state.quat[2], state.quat[3]).normalized();
  const Eigen::Matrix3d R = q.toRotationMatrix();  // body -> world; sign of q irrelevant

  // Altitude PID: the vertical acceleration wanted.
  const double z_error = setpoint.pos[2] - state.pos[2];
  const double az =
      setpoint.acc[2] + k.kp_z * z_error + k.kd_z * (setpoint.vel[2] - state.vel[2]) + integral_z_;

  const Eigen::Vector3d force = ThrustVector(k, m, g, setpoint, az, &out);
  const Eigen::Vector3d b3d = force.normalized();  // desired body z, world; b3d.z() > 0

  // Desired attitude: body z along F, body x as close as possible to the yaw heading b1c.
  // |b3d x b1c| >= b3d.z() > 0 since b1c is horizontal, so no singularity.
  const Eigen::Vector3d b1c(std::cos(setpoint.yaw), std::sin(setpoint.yaw), 0);
  const Eigen::Vector3d b1d = b3d.cross(b1c).normalized().cross(b3d);  // b2d x b3d

  // Collective: the part of F along the current body z (Lee et al. eq. (15)); none when the body
  // points away from F (e.g. while recovering from a large tilt).
  out.thrust = std::max(0.0, force.dot(R.col(2)));

  const Eigen::Vector3d error = AttitudeError(q, R, b3d, b1d, &out);

  // Attitude P -> body rate reference; rate PI -> angular acceleration; torque with the
  // gyroscopic term w x J w.
  const Eigen::Vector3d rate_ref(k.k_att * error.x(), k.k_att * error.y(), k.k_yaw * error.z());
  const Eigen::Vector3d rate(state.gyro[0], state.gyro[1], state.gyro[2]);
  const Eigen::Vector3d J(vehicle_.inertia[0], vehicle_.inertia[1], vehicle_.inertia[2]);
  const Eigen::Vector3d rate_error = rate_ref - rate;
  const Eigen::Vector3d alpha = k.k_rate * rate_error + integral_rate_;
  const Eigen::Vector3d torque = J.cwiseProduct(alpha) + rate.cross(J.cwiseProduct(rate));
  out.mix = mixer_.Mix(Wrench(out.thrust, torque.x(), torque.y(), torque.z()),
                       Mixer::Priority::kRollPitchFirst);
  out.ctrl = out.mix.ctrl;
  for (int i = 0; i < 3; ++i) {
    out.force[i] = force[i];
    out.attitude_error[i] = error[i];
    out.rate_ref[i] = rate_ref[i];
    out.torque[i] = torque[i];
  }

  Integrate(k, out, rate_error, m * (g + az), z_error, dt, &integral_rate_, &integral_z_);
  return out;
}

}  // namespace mjf::attitude
