// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/continuous_smc.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

void ContinuousSmcParams::Validate() const {
  ValidateGains(gains);
  if (!(rho > 0.0 && std::isfinite(rho))) {
    std::ostringstream out;
    out << "attribute 'rho': rho > 0 is required by Theorem 1 (got " << rho << ")";
    throw std::invalid_argument(out.str());
  }
  if (reaching == Reaching::kExponential && !(q > 0.0 && std::isfinite(q))) {
    std::ostringstream out;
    out << "attribute 'q' with 'reaching' = 'exponential': q > 0 is required (got " << q << ")";
    throw std::invalid_argument(out.str());
  }
  ValidateLeaderBounds(u_min, u_max);
  ValidateSign(sign, boundary_layer);
}

Compensation ParseCompensation(const std::string& text) {
  if (text == "lower_bound") return Compensation::kLowerBound;
  if (text == "switching") return Compensation::kSwitching;
  throw std::invalid_argument("attribute 'compensation': '" + text +
                              "' is not one of 'lower_bound', 'switching'");
}

Reaching ParseReaching(const std::string& text) {
  if (text == "constant") return Reaching::kConstant;
  if (text == "exponential") return Reaching::kExponential;
  throw std::invalid_argument("attribute 'reaching': '" + text +
                              "' is not one of 'constant', 'exponential'");
}

ContinuousSmc::ContinuousSmc(const Graph& graph, const ContinuousSmcParams& params)
    : SolvedLaw(graph), params_(Validated(params)) {}

void ContinuousSmc::Update(const FormationInput& input) {
  const int n = graph_.num_followers();
  const double k1 = params_.gains.k1, k2 = params_.gains.k2;
  const double mu1 = 0.5 * (params_.u_max + params_.u_min);  // eq. (48)'s mu1
  const double mu2 = 0.5 * (params_.u_max - params_.u_min);  // eq. (48)'s mu2
  ComputeErrorAndSliding(graph_, params_.gains, input.leader_pv, input.follower_pv, input.shape_now,
                         error_.data(), sliding_.data());
  // eq. (33) rearranged: k2 L_H (U - F_a) = -k1 E_v + k2 H U0 - rho sgn(S) [- q S], because
  // (L_H (x) KA) X - H1 (x) KA x_0 - (L_H (x) K) F' = k1 E_v + k2 L_H F_a (L_H 1 = H 1).
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double s = sliding_[2 * i + axis];
      const double sign = SwitchingSign(s, params_.sign, params_.boundary_layer);
      const double leader_input = params_.compensation == Compensation::kLowerBound
                                      ? params_.u_min      // eq. (30) as printed
                                      : mu1 - mu2 * sign;  // u0~_i of eq. (48)
      double reaching = params_.rho * sign;                // rho sgn(s_i), eq. (30)
      if (params_.reaching == Reaching::kExponential) reaching += params_.q * s;
      rhs_(i, axis) =
          (-k1 * error_[4 * i + 2 + axis] - reaching) / k2 + graph_.leader_weight(i) * leader_input;
    }
  }
  solver_.SolveInPlace(rhs_);  // (L_H (x) KB)^-1 of eq. (33)
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      acceleration_[2 * i + axis] = input.shape_now[6 * i + 4 + axis] + rhs_(i, axis);
    }
  }
  if (reaching_time_bound_ < 0.0) {
    double bound = 0.0;
    for (double s : sliding_) {
      const double t = params_.reaching == Reaching::kConstant
                           ? std::abs(s) / params_.rho
                           : std::log1p(params_.q * std::abs(s) / params_.rho) / params_.q;
      if (t > bound) bound = t;
    }
    reaching_time_bound_ = bound;
  }
}

}  // namespace mjf::formation
