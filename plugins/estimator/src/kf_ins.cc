// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/estimator/kf_ins.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "mjformation/time_steps.hpp"

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
  Require(c.aiding_period == 0 || WholeSteps(c.aiding_period, c.timestep) >= 1,
          "aiding_period must be 0 (any step) or a whole number of steps");
  // Squared into the initial covariance: a negative value would pass as its absolute value.
  for (const auto& [value, name] : {std::pair{c.initial_position_std, "initial_position_std"},
                                    std::pair{c.initial_velocity_std, "initial_velocity_std"},
                                    std::pair{c.initial_bias_std, "initial_bias_std"}}) {
    Require(value >= 0 && std::isfinite(value * value),
            std::string(name) + " must be a number >= 0 whose square is finite");
  }
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
  window_steps_ = StepsAtOrAfter(c.history, dt) + 1;
  period_steps_ = c.aiding_period == 0 ? 1 : WholeSteps(c.aiding_period, dt);
  // A late measurement's step lies in the window_steps_ steps before now and on the schedule.
  history_.resize(static_cast<size_t>((window_steps_ - 1) / period_steps_ + 1));
  // Every correction the state holds, allocated once: none in flight.
  corrections_.reserve(max_corrections());
}

size_t KfIns::SlotOf(int64_t step) const {
  return static_cast<size_t>((step / period_steps_) % static_cast<int64_t>(history_.size()));
}

void KfIns::TransitionPower(int64_t m, StateVec* x) const {
  const double t = static_cast<double>(m) * config_.timestep;
  const double c = config_.timestep * config_.timestep * static_cast<double>(m) * (m + 1) / 2.0;
  x->segment<3>(0) += t * x->segment<3>(3) - c * x->segment<3>(6);
  x->segment<3>(3) -= t * x->segment<3>(6);
  x->segment<3>(9) *= std::pow(wander_keep_, static_cast<double>(m));
}

void KfIns::TransitionPower(int64_t m, StateMat* P) const {
  const double t = static_cast<double>(m) * config_.timestep;
  const double c = config_.timestep * config_.timestep * static_cast<double>(m) * (m + 1) / 2.0;
  const double keep = std::pow(wander_keep_, static_cast<double>(m));
  P->middleRows<3>(0) += t * P->middleRows<3>(3) - c * P->middleRows<3>(6);
  P->middleRows<3>(3) -= t * P->middleRows<3>(6);
  P->middleRows<3>(9) *= keep;
  P->middleCols<3>(0) += t * P->middleCols<3>(3) - c * P->middleCols<3>(6);
  P->middleCols<3>(3) -= t * P->middleCols<3>(6);
  P->middleCols<3>(9) *= keep;
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
  if (step_ % period_steps_ == 0) {  // a step a measurement can be taken at
    Slot& slot = history_[SlotOf(step_)];
    slot.step = step_;
    slot.x = x_;
    slot.P = P_;
  }
  PropagateOnce(specific_force_world);
  step_ = step;
  const int64_t oldest = step_ - window_steps_;
  corrections_.erase(std::remove_if(corrections_.begin(), corrections_.end(),
                                    [oldest](const Correction& c) { return c.last < oldest; }),
                     corrections_.end());
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
  const int64_t taken = NearestStep(m.time_taken, config_.timestep);
  if (taken > step_) throw std::logic_error("KfIns::Fuse: a measurement from the future");
  if (taken == step_) {
    const bool ok = Update(m);
    (ok ? fused_ : rejected_) += 1;
    return ok;
  }
  if (taken % period_steps_ != 0) {
    throw std::logic_error("KfIns::Fuse: a measurement taken at step " + std::to_string(taken) +
                           ", off the aiding schedule (every " + std::to_string(period_steps_) +
                           " steps: aiding_period)");
  }
  const Slot& slot = history_[SlotOf(taken)];
  if (taken < step_ - window_steps_ || slot.step != taken) {
    ++too_old_;
    return false;
  }
  // The posterior at `taken` as later fusions left it, then fused there.
  StateVec x_then = slot.x;
  StateMat P_then = slot.P;
  for (const Correction& c : corrections_) {
    if (c.step > taken || c.last < taken) continue;
    StateVec dx = c.dx;
    StateMat dP = c.dP;
    TransitionPower(taken - c.step, &dx);
    TransitionPower(taken - c.step, &dP);
    x_then += dx;
    P_then += dP;
  }
  const StateVec x_now = x_;
  const StateMat P_now = P_;
  x_ = x_then;
  P_ = P_then;
  // (A refused block leaves no trace; an accepted one of a refused pair does, as on time.)
  const bool ok = Update(m);
  (ok ? fused_ : rejected_) += 1;
  Correction c{taken, step_ - 1, x_ - x_then, P_ - P_then};
  StateVec dx = c.dx;
  StateMat dP = c.dP;
  TransitionPower(step_ - taken, &dx);
  TransitionPower(step_ - taken, &dP);
  x_ = x_now + dx;
  P_ = P_now + dP;
  if (corrections_.size() >= max_corrections()) {
    throw std::length_error("KfIns::Fuse: more than " + std::to_string(max_corrections()) +
                            " late measurements within the history window of " +
                            std::to_string(window_steps_) +
                            " steps (the filter's state bound); lower the aiding rates");
  }
  corrections_.push_back(std::move(c));
  return ok;
}

}  // namespace mjf::estimator
