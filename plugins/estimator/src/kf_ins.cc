// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/estimator/kf_ins.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mjf::estimator {
namespace {

// A stated sigma of zero would make S singular once P has converged: every sensor is taken to be
// at least this good, not exact (1 um, 1 um/s; far below any preset).
constexpr double kMinStd = 1e-6;

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("kf_ins: " + what);
}

}  // namespace

KfIns::KfIns(const KfInsConfig& c) : config_(c) {
  Require(c.timestep > 0 && std::isfinite(c.timestep), "timestep must be > 0");
  Require(c.accel_noise_density >= 0 && std::isfinite(c.accel_noise_density),
          "accel_noise_density must be a finite number >= 0");
  Require(c.accel_bias_walk >= 0 && std::isfinite(c.accel_bias_walk),
          "accel_bias_walk must be a finite number >= 0");
  Require(c.history >= 0 && c.history <= 10 && std::isfinite(c.history),
          "history must be in [0, 10] s");
  Require(c.gate_sigma > 0, "gate_sigma must be > 0");
  Require(c.position_wander_std >= 0 && std::isfinite(c.position_wander_std),
          "position_wander_std must be a finite number >= 0");
  Require(c.position_wander_tau > 0 && std::isfinite(c.position_wander_tau),
          "position_wander_tau must be a finite number > 0 s");
  const double dt = c.timestep;
  // Semi-implicit Euler, the integrator of the simulated vehicle (MuJoCo's "Euler"):
  // v+ = v + a dt, p+ = p + v+ dt, with a = f_world + g - b; the wander w+ = phi w + drive,
  // phi = exp(-dt / tau), the sensor model's process sampled every physics step.
  wander_keep_ = std::exp(-dt / c.position_wander_tau);
  F_.setIdentity();
  F_.block<3, 3>(0, 3) = dt * Mat3::Identity();
  F_.block<3, 3>(0, 6) = -dt * dt * Mat3::Identity();
  F_.block<3, 3>(3, 6) = -dt * Mat3::Identity();
  F_.block<3, 3>(9, 9) = wander_keep_ * Mat3::Identity();
  // Discrete process noise of white acceleration noise of density n (continuous white noise
  // sampled over dt, van Loan): Q_vv = n^2 dt, Q_pv = n^2 dt^2 / 2, Q_pp = n^2 dt^3 / 3; the
  // bias walk w adds w^2 dt to Q_bb; the wander's drive keeps its variance at sigma^2:
  // Q_ww = sigma^2 (1 - phi^2).
  const double n2 = c.accel_noise_density * c.accel_noise_density;
  const double w2 = c.accel_bias_walk * c.accel_bias_walk;
  const double s2 = c.position_wander_std * c.position_wander_std;
  Q_.setZero();
  Q_.block<3, 3>(0, 0) = n2 * dt * dt * dt / 3.0 * Mat3::Identity();
  Q_.block<3, 3>(0, 3) = n2 * dt * dt / 2.0 * Mat3::Identity();
  Q_.block<3, 3>(3, 0) = Q_.block<3, 3>(0, 3);
  Q_.block<3, 3>(3, 3) = n2 * dt * Mat3::Identity();
  Q_.block<3, 3>(6, 6) = w2 * dt * Mat3::Identity();
  Q_.block<3, 3>(9, 9) = s2 * (1.0 - wander_keep_ * wander_keep_) * Mat3::Identity();
  g_ = Vec3(0, 0, -c.gravity);
  x_ << c.initial_position, c.initial_velocity, Vec3::Zero(), Vec3::Zero();
  P_.setZero();
  // The wander starts stationary (the sensor model draws its first sample so).
  P_.diagonal() << Vec3::Constant(c.initial_position_std * c.initial_position_std),
      Vec3::Constant(c.initial_velocity_std * c.initial_velocity_std),
      Vec3::Constant(c.initial_bias_std * c.initial_bias_std), Vec3::Constant(s2);
  window_steps_ = static_cast<int64_t>(std::ceil(c.history / dt - 1e-9)) + 1;
}

void KfIns::PropagateOnce(const Vec3& f) {
  const double dt = config_.timestep;
  const Vec3 a = f + g_ - x_.segment<3>(6);
  x_.segment<3>(3) += a * dt;
  x_.segment<3>(0) += x_.segment<3>(3) * dt;
  x_.segment<3>(9) *= wander_keep_;
  // P = F P F^T + Q with F's block structure (identity plus dt, -dt^2, -dt blocks and phi on the
  // wander): row-block then column-block updates, a fraction of the dense products' cost (the
  // same algebra).
  const double dt2 = dt * dt;
  P_.middleRows<3>(0) += dt * P_.middleRows<3>(3) - dt2 * P_.middleRows<3>(6);
  P_.middleRows<3>(3) -= dt * P_.middleRows<3>(6);
  P_.middleRows<3>(9) *= wander_keep_;
  P_.middleCols<3>(0) += dt * P_.middleCols<3>(3) - dt2 * P_.middleCols<3>(6);
  P_.middleCols<3>(3) -= dt * P_.middleCols<3>(6);
  P_.middleCols<3>(9) *= wander_keep_;
  P_ += Q_;
}

void KfIns::Propagate(int64_t step, const Vec3& specific_force_world) {
  if (step != step_ + 1) {
    throw std::logic_error("KfIns::Propagate: expected step " + std::to_string(step_ + 1) +
                           ", got " + std::to_string(step));
  }
  history_.push_back({step_, x_, P_, specific_force_world});
  while (static_cast<int64_t>(history_.size()) > window_steps_) history_.pop_front();
  PropagateOnce(specific_force_world);
  step_ = step;
}

// One 3-axis sample: position z = p + w + white (H = [I 0 0 I]) or velocity z = v + white
// (H = [0 I 0 0]). Sequential scalar updates would differ from a joint one only in rounding; the
// block is gated as a whole (every axis within the gate).
bool KfIns::UpdateBlock(bool position, const Vec3& z, const Vec3& std) {
  Eigen::Matrix<double, 3, kStates> H = Eigen::Matrix<double, 3, kStates>::Zero();
  H.block<3, 3>(0, position ? 0 : 3).setIdentity();
  if (position) H.block<3, 3>(0, 9).setIdentity();
  const Vec3 s = std.cwiseMax(kMinStd);
  const Mat3 R = s.cwiseProduct(s).asDiagonal();
  const Vec3 innovation = z - H * x_;
  const Eigen::Matrix<double, kStates, 3> PHt = P_ * H.transpose();
  const Mat3 S = H * PHt + R;
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(innovation[k]) <= config_.gate_sigma * std::sqrt(S(k, k)))) return false;
  }
  const Eigen::Matrix<double, kStates, 3> K = PHt * S.inverse();
  x_ += K * innovation;
  // Joseph form: stays symmetric positive semi-definite when K is applied with rounding.
  const StateMat I_KH = StateMat::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
  return true;
}

bool KfIns::Update(const AidingSample& m) {
  bool accepted = true;
  if (m.has_position) accepted = UpdateBlock(true, m.position, m.position_std) && accepted;
  if (m.has_velocity) accepted = UpdateBlock(false, m.velocity, m.velocity_std) && accepted;
  return accepted;
}

bool KfIns::Fuse(const AidingSample& m) {
  const int64_t taken = std::llround(m.time_taken / config_.timestep);
  if (taken > step_) throw std::logic_error("KfIns::Fuse: a measurement from the future");
  if (taken == step_) {
    const bool ok = Update(m);
    (ok ? fused_ : rejected_) += 1;
    return ok;
  }
  if (history_.empty() || taken < history_.front().step) {
    ++too_old_;
    return false;
  }
  // Rewind to the posterior at the step it was taken, fuse there, re-propagate to now with the
  // stored inputs, re-storing each step's corrected posterior.
  auto slot = history_.begin() + (taken - history_.front().step);
  x_ = slot->x;
  P_ = slot->P;
  const bool ok = Update(m);
  (ok ? fused_ : rejected_) += 1;
  for (; slot != history_.end(); ++slot) {
    slot->x = x_;
    slot->P = P_;
    PropagateOnce(slot->input);
  }
  return ok;
}

}  // namespace mjf::estimator
