// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <cmath>
#include <limits>
#include <mjformation/formation/discrete_smc.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {

void DiscreteSmcParams::Validate() const {
  ValidateGains(gains);
  auto require_positive = [](double value, const char* key, const char* source) {
    if (!(value > 0.0 && std::isfinite(value))) {
      std::ostringstream out;
      out << "attribute '" << key << "': " << key << " > 0 is required by " << source << " (got "
          << value << ")";
      throw std::invalid_argument(out.str());
    }
  };
  require_positive(eps, "eps", "Theorem 2");
  require_positive(q, "q", "Theorem 2");
  require_positive(period, "period", "Algorithm 2 (sample period T)");
  if (!(1.0 - q * period > 0.0)) {
    std::ostringstream out;
    out << "attribute 'q' with 'period': 1 - q*T > 0 is required by Theorem 2 (got q = " << q
        << ", T = " << period << ")";
    throw std::invalid_argument(out.str());
  }
  require_positive(eta0, "eta0", "eq. (49)");
  if (require_stable_surface && !(period * gains.k1 / gains.k2 < 2.0)) {
    std::ostringstream out;
    out << "attribute 'k' with 'period': T*k1/k2 < 2 is required for the discrete sliding "
           "surface to be stable (e_p(k+1) = (1 - T k1/k2) e_p(k) on s = 0; not stated in "
           "Algorithm 2) (got k1 = "
        << gains.k1 << ", k2 = " << gains.k2 << ", T = " << period << ")";
    throw std::invalid_argument(out.str());
  }
  ValidateLeaderBounds(u_min, u_max);
  ValidateSign(sign, boundary_layer);
  ValidateAccelLimit();
}

DiscreteSmc::DiscreteSmc(const Graph& graph, const DiscreteSmcParams& params)
    : graph_(WithSpanningTree(graph)),
      params_(Validated(params)),
      solver_(graph_.laplacian_h()),
      acceleration_(2 * graph_.num_followers(), 0.0),
      sliding_(2 * graph_.num_followers(), 0.0),
      error_(4 * graph_.num_followers(), 0.0),
      rhs_(graph_.num_followers(), 2) {
  if (constrained()) InitAccelLimit();
}

void DiscreteSmc::Update(const FormationInput& input) {
  const int n = graph_.num_followers();
  const double k1 = params_.gains.k1, k2 = params_.gains.k2, T = params_.period;
  const double kb = k2 * T;                                  // KB, model (40)
  const double mu1 = 0.5 * (params_.u_max + params_.u_min);  // eq. (48)
  const double mu2 = 0.5 * (params_.u_max - params_.u_min);  // eq. (48)
  ComputeErrorAndSliding(graph_, params_.gains, input.leader_pv, input.follower_pv, input.shape_now,
                         error_.data(), sliding_.data());
  // eq. (53) rearranged: with y_i = KA (x_i - x_0) - K f_i(k+1), KA x = k1 (p + T v) + k2 v,
  // (L_H (x) KA) X - H1 (x) KA x_0 - (L_H (x) K) F(k+1) = L_H Y, hence
  // U = -Y / KB + L_H^-1 [ H U0~ - ((qT - 1) S + eps T sgn(S)) / KB ].
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double s = sliding_[2 * i + axis];
      const double sign = SwitchingSign(s, params_.sign, params_.boundary_layer);
      const double leader_input = mu1 - mu2 * sign;  // u0~_i(k), eq. (48)
      const double reaching = (params_.q * T - 1.0) * s + params_.eps * T * sign;  // eq. (48)
      rhs_(i, axis) = graph_.leader_weight(i) * leader_input - reaching / kb;
    }
  }
  solver_.SolveInPlace(rhs_);  // (L_H (x) KB)^-1 of eq. (53)
  const double* x0 = input.leader_pv;
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double p = input.follower_pv[4 * i + axis] - x0[axis];
      const double v = input.follower_pv[4 * i + 2 + axis] - x0[2 + axis];
      const double y = k1 * (p + T * v) + k2 * v - k1 * input.shape_next[6 * i + axis] -
                       k2 * input.shape_next[6 * i + 2 + axis];  // KA x - K f(k+1), eq. (53)
      acceleration_[2 * i + axis] = -y / kb + rhs_(i, axis);
    }
  }
  if (constrained()) ApplyAccelLimit(input);
}

double DiscreteSmc::delta1(int i) const {
  const DiscreteSmcParams& p = params_;
  const double kb = p.gains.k2 * p.period;
  return (p.eps * p.period + graph_.leader_weight(i) * kb * (p.u_max - p.u_min) + p.eta0) /
         (2.0 - p.q * p.period);  // eq. (49)
}

double DiscreteSmc::delta2(int i) const {
  const DiscreteSmcParams& p = params_;
  const double kb = p.gains.k2 * p.period;
  return p.eps * p.period + graph_.leader_weight(i) * kb * (p.u_max - p.u_min);  // eq. (50)
}

double DiscreteSmc::delta(int i) const { return std::max(delta1(i), delta2(i)); }  // Theorem 2

double DiscreteSmc::delta() const {
  double largest = 0.0;
  for (int i = 0; i < graph_.num_followers(); ++i) largest = std::max(largest, delta(i));
  return largest;
}

double DiscreteSmc::error_bound() const {
  const double k_sum = params_.gains.k1 + params_.gains.k2;
  return norm_inv_lh() * std::sqrt(static_cast<double>(graph_.num_followers())) * delta() /
         (k_sum * std::sqrt(2.0));  // eq. (47) as EQUATIONS.md reads it
}

double DiscreteSmc::ultimate_error_bound() const {
  const int n = graph_.num_followers();
  const double k1 = params_.gains.k1, k2 = params_.gains.k2, T = params_.period;
  const double a = T * k1 / k2;
  if (!(a < 2.0)) return std::numeric_limits<double>::infinity();
  // b = L_H^-1 Delta (both columns carry the same Delta; the solver works on pairs).
  Eigen::Matrix<double, Eigen::Dynamic, 2> b(n, 2);
  for (int i = 0; i < n; ++i) b(i, 0) = b(i, 1) = delta(i);
  LaplacianSolver solver(graph_.laplacian_h());
  solver.SolveInPlace(b);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double p_bound = (T / k2) * b(i, 0) / (1.0 - std::abs(1.0 - a));
    const double v_bound = (b(i, 0) + k1 * p_bound) / k2;
    sum += 2.0 * (p_bound * p_bound + v_bound * v_bound);
  }
  return std::sqrt(sum);
}

}  // namespace mjf::formation
