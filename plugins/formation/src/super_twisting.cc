// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <cmath>
#include <mjformation/formation/super_twisting.hpp>

namespace mjf::formation {

void SuperTwistingParams::Validate() const {
  ValidateGains(gains);
  RequirePositive(lambda, "lambda", "the super-twisting algorithm (Levant 1993)");
  RequirePositive(alpha, "alpha", "the super-twisting algorithm (Levant 1993)");
}

double SuperTwistingTimeBound(double lambda, double alpha, double s0, double w0) {
  // P = [[a, b], [b, c]] solves A' P + P A = -I for A = [[-lambda/2, 1/2], [-alpha, 0]]:
  // (2,2) gives b = -1, (1,1) -lambda a - 2 alpha b = -1, (1,2) -lambda b/2 - alpha c + a/2 = 0.
  const double b = -1.0;
  const double a = (1.0 + 2.0 * alpha) / lambda;
  const double c = (lambda + a) / (2.0 * alpha);
  const double mean = 0.5 * (a + c), radius = std::hypot(0.5 * (a - c), b);
  const double p_min = mean - radius, p_max = mean + radius;  // eigenvalues of P
  const double g = std::sqrt(p_min) / p_max;                  // lambda_min(Q) = 1
  const double z1 = SignedPower(s0, 0.5);                     // zeta = (|s|^(1/2) sgn s, w)
  const double v0 = a * z1 * z1 + 2.0 * b * z1 * w0 + c * w0 * w0;
  return 2.0 * std::sqrt(v0) / g;  // T <= 2 V(0)^(1/2) / g (Moreno & Osorio 2012)
}

bool LevantConditionHolds(double lambda, double alpha, double c) {
  return alpha > c && lambda * lambda >= 4.0 * c * (alpha + c) / (alpha - c);
}

SuperTwisting::SuperTwisting(const Graph& graph, const SuperTwistingParams& params)
    : SolvedLaw(graph), params_(Validated(params)), w_(2 * graph_.num_followers(), 0.0) {}

void SuperTwisting::Reset() {
  std::fill(w_.begin(), w_.end(), 0.0);
  clock_.Reset();
  reaching_time_bound_ = -1.0;
}

void SuperTwisting::Update(const FormationInput& input, double time) {
  const int n = graph_.num_followers();
  const double k1 = params_.gains.k1, k2 = params_.gains.k2;
  const double dt = clock_.Advance(time);
  ComputeErrorAndSliding(graph_, params_.gains, input.leader_pv, input.follower_pv, input.shape_now,
                         error_.data(), sliding_.data());  // s_i = K e_i, eq. (17)
  if (reaching_time_bound_ < 0.0) {
    double bound = 0.0;
    for (double s : sliding_) {
      bound = std::max(bound, SuperTwistingTimeBound(params_.lambda, params_.alpha, s, 0.0));
    }
    reaching_time_bound_ = bound;
  }
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const int j = 2 * i + axis;
      const double s = sliding_[j];
      // w_i' = -alpha sgn(s_i) over the step that ends now (Euler, sign taken at its end).
      w_[j] -= dt * params_.alpha * (s > 0.0 ? 1.0 : (s < 0.0 ? -1.0 : 0.0));
      const double v = -params_.lambda * SignedPower(s, 0.5) + w_[j];  // V_i of the STA
      rhs_(i, axis) = (v - k1 * error_[4 * i + 2 + axis]) / k2;        // (V - k1 E_v) / k2
    }
  }
  solver_.SolveInPlace(rhs_);  // L_H^-1
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      acceleration_[2 * i + axis] = input.shape_now[6 * i + 4 + axis] + rhs_(i, axis);  // F_a +
    }
  }
}

}  // namespace mjf::formation
