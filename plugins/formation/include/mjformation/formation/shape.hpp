// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Desired formations (Definition 1): offsets f_i(t) = [f_ip, f_iv] of each follower from the
// leader, per horizontal axis, with their accelerations f_ia (needed by eq. (30)).
#ifndef MJFORMATION_FORMATION_SHAPE_HPP_
#define MJFORMATION_FORMATION_SHAPE_HPP_

#include <mjformation/plugin.h>

#include <memory>
#include <vector>

namespace mjf::formation {

// Layout of Shape::Evaluate's output for follower i: out[6*i + k].
enum ShapeComponent { kShapePx = 0, kShapePy, kShapeVx, kShapeVy, kShapeAx, kShapeAy };

class Shape {  // desired offsets f_i(t) from the leader (Definition 1)
 public:
  virtual ~Shape() = default;
  virtual int num_followers() const = 0;
  // out[6*i+k], k = (px, py, vx, vy, ax, ay) in m, m/s, m/s^2. Must not allocate.
  virtual void Evaluate(double t, double* out) const = 0;
  // out[0..5]: follower i's entries of Evaluate, bit for bit, in O(1) of num_followers (what a
  // per-agent instance needs for itself and its neighbours). Must not allocate.
  virtual void EvaluateOne(double t, int i, double* out) const = 0;
};

// The paper's rotating circle (section 6): theta_i = omega t + phase0 + i*phase_step (i 0-based),
// f_i = radius [cos theta_i, sin theta_i] and its derivatives. Paper: radius 10 m,
// omega 0.314 rad/s, phase0 0, phase_step pi/3. Throws std::invalid_argument on bad input.
std::unique_ptr<Shape> MakeCircleShape(int n_followers, double radius, double omega, double phase0,
                                       double phase_step);

// One sinusoid: amplitude * sin(omega t + phase).
struct Sinusoid {
  double amplitude = 0.0;  // m
  double omega = 0.0;      // rad/s
  double phase = 0.0;      // rad
};
// One axis of one follower: f_p(t) = sum_k polynomial[k] t^k + sum sinusoids. polynomial[0] is
// the constant offset. Velocity and acceleration are the exact derivatives (always consistent).
struct AxisTerms {
  std::vector<double> polynomial;
  std::vector<Sinusoid> sinusoids;
};
struct FollowerTerms {
  AxisTerms x;
  AxisTerms y;
};
// A general analytic shape, one FollowerTerms per follower. Throws on non-finite coefficients.
std::unique_ptr<Shape> MakeTermsShape(std::vector<FollowerTerms> followers);

// A sampled table: times (strictly increasing, >= 2 entries) and samples[(k*n + i)*4 + c],
// c = (px, py, vx, vy) of follower i at times[k]. Between samples the position is the cubic
// Hermite interpolant through (p, v) at both ends, the velocity is interpolated linearly and the
// acceleration is the slope of that line; beyond the table both are extrapolated with the end
// velocity (acceleration 0). Tables whose velocities do not match their positions are not
// consistent: CheckShapeConsistency finds them. Throws std::invalid_argument on bad sizes.
std::unique_ptr<Shape> MakeSampledShape(int n_followers, std::vector<double> times,
                                        std::vector<double> samples);

// Which form of Algorithms 1/2's condition f_ip' = f_iv CheckShapeConsistency tests on each
// sample interval [t_k, t_k + dt].
enum class ConsistencyForm {
  // (f_ip(t+dt) - f_ip(t)) / dt vs f_iv(t + dt/2), and the same for f_iv vs f_ia: second order
  // in dt, so a consistent smooth shape passes with a small tol; a jump of f_ia (a table's
  // piecewise-linear velocity) is tolerated when it sits on the sampling grid t0 + k dt.
  kMidpoint,
  // Algorithm 2 as printed: (f_ip(k+1) - f_ip(k)) / dt vs f_iv(k). First order in dt: the
  // paper's own circle misses it by dt * r w^2 / 2 (see README).
  kForwardDifference,
};

// Algorithms 1/2 step "f_ip' = f_iv" (and f_iv' = f_ia, used by eq. (30)): throws
// std::invalid_argument naming follower (1-based), axis and time when the mismatch in m/s
// (resp. m/s^2) exceeds tol anywhere on [t0, t1] sampled at dt, or when a value is not finite.
void CheckShapeConsistency(const Shape& shape, double t0, double t1, double dt, double tol,
                           ConsistencyForm form = ConsistencyForm::kMidpoint);

// Wraps for plugin.h (self = &shape): the shape must outlive the returned struct.
mjfShape ToAbi(const Shape& shape);

// Wraps an ABI shape as a Shape (does not own it).
class AbiShape : public Shape {
 public:
  explicit AbiShape(const mjfShape& shape);  // throws std::invalid_argument if incomplete
  int num_followers() const override { return shape_.n_followers; }
  void Evaluate(double t, double* out) const override { shape_.evaluate(shape_.self, t, out); }
  // Through evaluate_one; without it (a host that does not set it), from a whole evaluate() into
  // a scratch buffer sized once here: correct, but O(n_followers).
  void EvaluateOne(double t, int i, double* out) const override;

 private:
  mjfShape shape_;
  mutable std::vector<double> scratch_;  // [6 n] only when shape_.evaluate_one is NULL
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_SHAPE_HPP_
