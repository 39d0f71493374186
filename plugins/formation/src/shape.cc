// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <cmath>
#include <mjformation/formation/shape.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "mjformation/cubic_hermite.hpp"
#include "mjformation/time_steps.hpp"

namespace mjf::formation {
namespace {

class CircleShape : public Shape {
 public:
  CircleShape(int n, double radius, double omega, double phase0, double phase_step)
      : n_(n), radius_(radius), omega_(omega), phase0_(phase0), phase_step_(phase_step) {}
  int num_followers() const override { return n_; }
  void Evaluate(double t, double* out) const override {
    for (int i = 0; i < n_; ++i) EvaluateOne(t, i, out + 6 * i);
  }
  void EvaluateOne(double t, int i, double* f) const override {
    const double theta = omega_ * t + phase0_ + i * phase_step_;
    const double c = std::cos(theta), s = std::sin(theta);
    f[kShapePx] = radius_ * c;
    f[kShapePy] = radius_ * s;
    f[kShapeVx] = -radius_ * omega_ * s;
    f[kShapeVy] = radius_ * omega_ * c;
    f[kShapeAx] = -radius_ * omega_ * omega_ * c;
    f[kShapeAy] = -radius_ * omega_ * omega_ * s;
  }

 private:
  int n_;
  double radius_, omega_, phase0_, phase_step_;
};

// Value, first and second derivative of one axis' terms at t.
void EvaluateAxis(const AxisTerms& terms, double t, double* p, double* v, double* a) {
  double pos = 0.0, vel = 0.0, acc = 0.0;
  // Horner for the polynomial and its derivatives.
  const int degree = static_cast<int>(terms.polynomial.size()) - 1;
  for (int k = degree; k >= 0; --k) {
    acc = acc * t + 2.0 * vel;
    vel = vel * t + pos;
    pos = pos * t + terms.polynomial[k];
  }
  for (const Sinusoid& s : terms.sinusoids) {
    const double angle = s.omega * t + s.phase;
    pos += s.amplitude * std::sin(angle);
    vel += s.amplitude * s.omega * std::cos(angle);
    acc -= s.amplitude * s.omega * s.omega * std::sin(angle);
  }
  *p = pos;
  *v = vel;
  *a = acc;
}

class TermsShape : public Shape {
 public:
  explicit TermsShape(std::vector<FollowerTerms> followers) : followers_(std::move(followers)) {}
  int num_followers() const override { return static_cast<int>(followers_.size()); }
  void Evaluate(double t, double* out) const override {
    for (int i = 0; i < num_followers(); ++i) EvaluateOne(t, i, out + 6 * i);
  }
  void EvaluateOne(double t, int i, double* f) const override {
    EvaluateAxis(followers_[i].x, t, &f[kShapePx], &f[kShapeVx], &f[kShapeAx]);
    EvaluateAxis(followers_[i].y, t, &f[kShapePy], &f[kShapeVy], &f[kShapeAy]);
  }

 private:
  std::vector<FollowerTerms> followers_;
};

class SampledShape : public Shape {
 public:
  SampledShape(int n, std::vector<double> times, std::vector<double> samples)
      : n_(n), times_(std::move(times)), samples_(std::move(samples)) {}
  int num_followers() const override { return n_; }
  void Evaluate(double t, double* out) const override {
    const Interval at = Locate(t);  // one search for every follower
    for (int i = 0; i < n_; ++i) Fill(at, i, out + 6 * i);
  }
  void EvaluateOne(double t, int i, double* f) const override { Fill(Locate(t), i, f); }

 private:
  // Where t falls in the table: beyond an end (extrapolate from sample k by dt) or in
  // [t_k, t_k+1] at u = (t - t_k) / h with the cubic Hermite basis (mjformation/cubic_hermite.hpp).
  struct Interval {
    bool beyond = false;
    int k = 0;
    double dt = 0.0, h = 0.0, u = 0.0;
    HermiteBasis basis{};
  };
  Interval Locate(double t) const {
    Interval at;
    const int last = static_cast<int>(times_.size()) - 1;
    if (t <= times_.front() || t >= times_[last]) {
      at.beyond = true;
      at.k = t <= times_.front() ? 0 : last;  // extrapolate with the end velocity
      at.dt = t - times_[at.k];
      return at;
    }
    at.k = static_cast<int>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()) - 1;
    at.h = times_[at.k + 1] - times_[at.k];
    const double u = (t - times_[at.k]) / at.h;
    at.u = u;
    at.basis = CubicHermiteHorner(u);
    return at;
  }
  void Fill(const Interval& at, int i, double* f) const {
    if (at.beyond) {
      const double* s = Sample(at.k, i);
      for (int axis = 0; axis < 2; ++axis) {
        f[kShapePx + axis] = s[axis] + s[2 + axis] * at.dt;
        f[kShapeVx + axis] = s[2 + axis];
        f[kShapeAx + axis] = 0.0;
      }
      return;
    }
    const double* s0 = Sample(at.k, i);
    const double* s1 = Sample(at.k + 1, i);
    const double h = at.h;
    for (int axis = 0; axis < 2; ++axis) {
      const double p0 = s0[axis], p1 = s1[axis], v0 = s0[2 + axis], v1 = s1[2 + axis];
      f[kShapePx + axis] = at.basis.h00 * p0 + at.basis.h10 * h * v0 + at.basis.h01 * p1 +
                           at.basis.h11 * h * v1;  // Hermite
      f[kShapeVx + axis] = v0 + at.u * (v1 - v0);
      f[kShapeAx + axis] = (v1 - v0) / h;
    }
  }
  const double* Sample(int k, int i) const { return samples_.data() + (k * n_ + i) * 4; }
  int n_;
  std::vector<double> times_;
  std::vector<double> samples_;
};

void RequireFinite(double value, const std::string& what) {
  if (!std::isfinite(value)) throw std::invalid_argument(what + " must be finite");
}

void TrampolineEvaluate(const void* self, double t, double* out) {
  static_cast<const Shape*>(self)->Evaluate(t, out);
}

void TrampolineEvaluateOne(const void* self, double t, int follower, double* out) {
  static_cast<const Shape*>(self)->EvaluateOne(t, follower, out);
}

const char* AxisName(int axis) { return axis == 0 ? "x" : "y"; }

}  // namespace

std::unique_ptr<Shape> MakeCircleShape(int n_followers, double radius, double omega, double phase0,
                                       double phase_step) {
  if (n_followers < 1) throw std::invalid_argument("circle shape: at least one follower");
  RequireFinite(radius, "circle shape: radius");
  RequireFinite(omega, "circle shape: omega");
  RequireFinite(phase0, "circle shape: phase0");
  RequireFinite(phase_step, "circle shape: phase_step");
  return std::make_unique<CircleShape>(n_followers, radius, omega, phase0, phase_step);
}

std::unique_ptr<Shape> MakeTermsShape(std::vector<FollowerTerms> followers) {
  if (followers.empty()) throw std::invalid_argument("terms shape: at least one follower");
  for (size_t i = 0; i < followers.size(); ++i) {
    for (const AxisTerms* axis : {&followers[i].x, &followers[i].y}) {
      const std::string where = "terms shape: follower " + std::to_string(i + 1) + " axis " +
                                (axis == &followers[i].x ? "x" : "y");
      for (double c : axis->polynomial) RequireFinite(c, where + " polynomial coefficient");
      for (const Sinusoid& s : axis->sinusoids) {
        RequireFinite(s.amplitude, where + " sinusoid amplitude");
        RequireFinite(s.omega, where + " sinusoid omega");
        RequireFinite(s.phase, where + " sinusoid phase");
      }
    }
  }
  return std::make_unique<TermsShape>(std::move(followers));
}

std::unique_ptr<Shape> MakeSampledShape(int n_followers, std::vector<double> times,
                                        std::vector<double> samples) {
  if (n_followers < 1) throw std::invalid_argument("sampled shape: at least one follower");
  if (times.size() < 2) throw std::invalid_argument("sampled shape: at least 2 sample times");
  for (size_t k = 0; k < times.size(); ++k) {
    RequireFinite(times[k], "sampled shape: time " + std::to_string(k + 1));
    if (k > 0 && !(times[k] > times[k - 1])) {
      throw std::invalid_argument("sampled shape: times must increase strictly (time " +
                                  std::to_string(k + 1) + ")");
    }
  }
  if (samples.size() != times.size() * n_followers * 4) {
    throw std::invalid_argument("sampled shape: expected " +
                                std::to_string(times.size() * n_followers * 4) +
                                " sample values (times x followers x [px py vx vy]), got " +
                                std::to_string(samples.size()));
  }
  for (double v : samples) RequireFinite(v, "sampled shape: sample value");
  return std::make_unique<SampledShape>(n_followers, std::move(times), std::move(samples));
}

void CheckShapeConsistency(const Shape& shape, double t0, double t1, double dt, double tol,
                           ConsistencyForm form) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw std::invalid_argument("shape consistency: dt must be finite and > 0");
  }
  if (!std::isfinite(t0) || !std::isfinite(t1) || t1 < t0) {
    throw std::invalid_argument("shape consistency: need finite t0 <= t1");
  }
  if (!(tol >= 0.0)) throw std::invalid_argument("shape consistency: tol must be >= 0");
  const int n = shape.num_followers();
  std::vector<double> now(6 * n), middle(6 * n), next(6 * n);
  const long steps = static_cast<long>(StepsAtOrBefore(t1 - t0, dt));
  shape.Evaluate(t0, now.data());
  for (long k = 0; k < steps; ++k) {
    const double t = t0 + k * dt;
    shape.Evaluate(t0 + (k + 0.5) * dt, middle.data());
    shape.Evaluate(t0 + (k + 1) * dt, next.data());
    for (int i = 0; i < n; ++i) {
      for (int axis = 0; axis < 2; ++axis) {
        // order 0: f_ip' = f_iv; order 1: f_iv' = f_ia.
        for (int order = 0; order < 2; ++order) {
          const int value = 6 * i + 2 * order + axis, rate = value + 2;
          const double rate_of_value = (next[value] - now[value]) / dt;
          const double stated = form == ConsistencyForm::kMidpoint ? middle[rate] : now[rate];
          const double mismatch = std::abs(rate_of_value - stated);
          if (!(mismatch <= tol)) {  // also catches NaN
            std::ostringstream out;
            out << "shape is inconsistent (Algorithms 1/2 require "
                << (order == 0 ? "f_ip' = f_iv" : "f_iv' = f_ia") << "): follower " << i + 1 << ", "
                << AxisName(axis) << " axis, at t = " << t << " s: "
                << (order == 0 ? "(f_ip(t+dt) - f_ip(t))/dt = " : "(f_iv(t+dt) - f_iv(t))/dt = ")
                << rate_of_value << " but " << (order == 0 ? "f_iv = " : "f_ia = ") << stated
                << (form == ConsistencyForm::kMidpoint ? " at t + dt/2" : " at t")
                << " (|difference| " << mismatch << " > tol " << tol << ", dt " << dt << ")";
            throw std::invalid_argument(out.str());
          }
        }
      }
    }
    std::swap(now, next);
  }
}

mjfShape ToAbi(const Shape& shape) {
  mjfShape abi{};
  abi.n_followers = shape.num_followers();
  abi.self = &shape;
  abi.evaluate = &TrampolineEvaluate;
  abi.evaluate_one = &TrampolineEvaluateOne;
  return abi;
}

AbiShape::AbiShape(const mjfShape& shape) : shape_(shape) {
  if (shape.n_followers < 1 || shape.evaluate == nullptr) {
    throw std::invalid_argument(
        "shape: the context's mjfShape is empty (no followers or no "
        "evaluate callback)");
  }
  if (shape.evaluate_one == nullptr) scratch_.resize(6 * static_cast<size_t>(shape.n_followers));
}

void AbiShape::EvaluateOne(double t, int i, double* out) const {
  if (shape_.evaluate_one) {
    shape_.evaluate_one(shape_.self, t, i, out);
    return;
  }
  shape_.evaluate(shape_.self, t, scratch_.data());
  std::copy_n(&scratch_[6 * static_cast<size_t>(i)], 6, out);
}

}  // namespace mjf::formation
