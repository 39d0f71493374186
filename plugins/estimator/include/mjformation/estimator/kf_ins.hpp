// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// KfIns: a linear Kalman filter per vehicle in the world frame, state x = (p, v, b, w) with b the
// accelerometer bias expressed in the world frame (it also absorbs the slowly varying tilt error
// of the attitude channel, g x delta-theta, which is a world-frame horizontal bias) and w the
// position source's Gauss-Markov wander (GNSS: satellite geometry, atmosphere), so that a
// position sample is z = p + w + white noise. Without wander (position_wander_std = 0) w stays
// exactly zero with zero variance and the filter is the (p, v, b) one. The input is the specific
// force rotated into the world frame by the attitude channel: a = R f + g - b.
// Measurements of p and/or v are fused at the time they were TAKEN: the filter keeps, for every
// step of a history window at least as long as the largest latency at which a measurement can be
// taken (every step, or only the aiding schedule's: multiples of the sensors' common period), the
// posterior of that step;
// a late measurement is fused at its own step, and the correction it makes there is carried to
// now in one go, x += F^n dx, P += F^n dP F^n' (n steps; exact: the state recursion is linear and
// the covariance recursion affine, so fusing on time and propagating gives the same). The stored
// posteriors it leaves stale are read corrected the same way by a later late measurement. Each
// fused quantity passes a 5-sigma innovation gate per axis or is counted as rejected.
// Pure C++17 + Eigen: no MuJoCo, no plugin ABI.
#ifndef MJFORMATION_ESTIMATOR_KF_INS_HPP_
#define MJFORMATION_ESTIMATOR_KF_INS_HPP_

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace mjf::estimator {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
constexpr int kStates = 12;  // p, v, b, w: three axes each
using StateVec = Eigen::Matrix<double, kStates, 1>;
using StateMat = Eigen::Matrix<double, kStates, kStates>;

struct KfInsConfig {
  double timestep = 0.001;  // s, one propagation per step
  double accel_noise_density =
      0.0;                       // m/s^2/sqrt(Hz): white specific-force noise the filter assumes
  double accel_bias_walk = 0.0;  // m/s^3/sqrt(Hz): bias random walk the filter assumes
  double history = 0.2;          // s kept for late measurements (>= the largest latency)
  // s: every measurement is taken at a multiple of it (the sensors' common sample period, from
  // t = 0), so only those steps' posteriors are kept; 0: at any step.
  double aiding_period = 0.0;
  double gate_sigma = 5.0;  // innovation gate, standard deviations per axis
  double gravity = 9.81;    // m/s^2, world -z
  Vec3 initial_position = Vec3::Zero();
  Vec3 initial_velocity = Vec3::Zero();
  double initial_position_std = 1.0;  // m
  double initial_velocity_std = 0.5;  // m/s
  double initial_bias_std = 0.2;      // m/s^2
  // The position source's first-order Gauss-Markov wander per axis: stationary 1 sigma and
  // correlation time (the sensor model's wander_sigma, wander_tau). 0: no wander state.
  double position_wander_std = 0.0;    // m
  double position_wander_tau = 100.0;  // s
};

// One aiding sample: which of p, v it carries, their values and 1-sigma noise per axis.
// position_std is the white part only: the wander is the filter's state w.
struct AidingSample {
  double time_taken = 0.0;
  bool has_position = false, has_velocity = false;
  Vec3 position = Vec3::Zero(), velocity = Vec3::Zero();
  Vec3 position_std = Vec3::Zero(), velocity_std = Vec3::Zero();
};

class KfIns {
 public:
  explicit KfIns(const KfInsConfig& config);  // throws std::invalid_argument on bad config

  // Propagates one step with the world-frame specific force of the step just ended
  // (a = f_world + g - b; f_world = R f_body): the state is then at `step`.
  void Propagate(int64_t step, const Vec3& specific_force_world);
  // Fuses a sample taken at or before the current step. Returns false when it is refused:
  // gated out (counted in rejected()) or older than the history (counted in too_old()).
  bool Fuse(const AidingSample& sample);

  const KfInsConfig& config() const { return config_; }
  int64_t step() const { return step_; }
  const StateVec& state() const { return x_; }
  const StateMat& covariance() const { return P_; }
  Vec3 position() const { return x_.segment<3>(0); }
  Vec3 velocity() const { return x_.segment<3>(3); }
  Vec3 bias() const { return x_.segment<3>(6); }
  Vec3 wander() const { return x_.segment<3>(9); }
  int64_t fused() const { return fused_; }
  int64_t rejected() const { return rejected_; }
  int64_t too_old() const { return too_old_; }

  // One step of the linear model (for tests and for the steady-state Riccati derivation).
  const StateMat& transition() const { return F_; }
  const StateMat& process_noise() const { return Q_; }

  // The posteriors the history keeps: the schedule's steps (multiples of the aiding period)
  // among the window's, at most (window - 1) / period + 1 of any window_steps consecutive steps.
  size_t history_slots() const { return history_.size(); }
  // The most late-fusion corrections the filter keeps at once (a fixed state size): a correction
  // lives one window, and position and velocity each arrive at most once per schedule step of it
  // (apart when their latencies differ), plus the window's two ends; Fuse refuses a late
  // measurement past it with this number.
  size_t max_corrections() const { return 2 * history_.size() + 2; }

  // The filter's state (plugin_state.hpp): estimate, covariance, step, the stored posteriors,
  // the corrections in flight (count, then max_corrections() slots) and the counts.
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(x_, P_, step_, history_, fused_, rejected_, too_old_);
    int64_t n = static_cast<int64_t>(corrections_.size());
    visit(n);
    // On a read, the count just read (within the table: a state of another configuration
    // cannot make it overflow).
    corrections_.resize(
        static_cast<size_t>(std::clamp<int64_t>(n, 0, static_cast<int64_t>(max_corrections()))));
    for (Correction& c : corrections_) visit(c);
    Correction blank{0, 0, StateVec::Zero(), StateMat::Zero()};  // the empty slots: zeros
    visit.Unused(max_corrections() - corrections_.size(), blank);
  }

 private:
  struct Slot {  // the posterior at `step` as it was stored
    int64_t step = -1;
    StateVec x;
    StateMat P;
    template <typename Visit>
    void VisitState(Visit& visit) {
      visit(step, x, P);
    }
  };
  // A fusion at the past step `step`, made when the slots up to `last` were stored: slot j in
  // [step, last] is read as x_j + F^(j - step) dx, P_j + F^(j - step) dP F^(j - step)'.
  struct Correction {
    int64_t step, last;
    StateVec dx;
    StateMat dP;
    template <typename Visit>
    void VisitState(Visit& visit) {
      visit(step, last, dx, dP);
    }
  };
  void PropagateOnce(const Vec3& specific_force_world);
  size_t SlotOf(int64_t step) const;  // the ring slot of a schedule step
  // x <- F^m x and P <- F^m P F^m' without the input (F^m in closed form: m steps of the
  // semi-implicit Euler give p + m dt v - dt^2 m (m + 1) / 2 b, v - m dt b, phi^m w).
  void TransitionPower(int64_t m, StateVec* x) const;
  void TransitionPower(int64_t m, StateMat* P) const;
  bool Update(const AidingSample& sample);
  // Fuses one 3-axis sample, z = p + w + white (position) or z = v + white (velocity).
  bool UpdateBlock(bool position, const Vec3& z, const Vec3& std);

  KfInsConfig config_;
  StateMat F_, Q_;
  Vec3 g_;
  double wander_keep_;  // exp(-dt / tau): w+ = wander_keep w + drive
  StateVec x_;
  StateMat P_;
  int64_t step_ = 0;
  int64_t window_steps_;
  int64_t period_steps_;       // the aiding schedule: measurements are taken at its multiples
  std::vector<Slot> history_;  // a ring: step s = k period in slot k % size, s >= step_ - window
  std::vector<Correction> corrections_;  // those still reaching a stored slot
  int64_t fused_ = 0, rejected_ = 0, too_old_ = 0;
};

}  // namespace mjf::estimator

#endif  // MJFORMATION_ESTIMATOR_KF_INS_HPP_
