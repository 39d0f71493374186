// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <mjformation/formation/discrete_smc_agent.hpp>
#include <stdexcept>

namespace mjf::formation {
namespace {

// y = k1 (p + T v) + k2 v - k1 f_p(k+1) - k2 f_v(k+1) for one axis, eq. (53) (absolute p).
double Y(const SlidingGains& k, double T, const double* pv, const double* f_next, int axis) {
  const double p = pv[axis], v = pv[2 + axis];
  return k.k1 * (p + T * v) + k.k2 * v - k.k1 * f_next[axis] - k.k2 * f_next[2 + axis];
}

}  // namespace

DiscreteSmcAgent::DiscreteSmcAgent(const DiscreteSmcParams& params, double leader_weight,
                                   std::vector<double> weights)
    : params_(Validated(params)),
      leader_weight_(leader_weight),
      weights_(std::move(weights)),
      kb_(params.gains.k2 * params.period),
      neighbour_y_(2 * weights_.size(), 0.0) {
  degree_ = leader_weight_;
  for (double a : weights_) degree_ += a;
  if (!(degree_ > 0.0)) {
    throw std::invalid_argument(
        "smc_discrete agent: this follower hears neither the leader nor a neighbour");
  }
}

void DiscreteSmcAgent::Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
                               const double* f_next, const double* neighbour_pv,
                               const double* neighbour_f_now, const double* neighbour_f_next) {
  const SlidingGains& k = params_.gains;
  const double T = params_.period;
  const double mu1 = 0.5 * (params_.u_max + params_.u_min);  // eq. (48)
  const double mu2 = 0.5 * (params_.u_max - params_.u_min);  // eq. (48)
  const int m = n_neighbours();
  for (int axis = 0; axis < 2; ++axis) {
    double e[2];  // position, velocity error of eq. (16)
    for (int c = 0; c < 2; ++c) {
      const int idx = axis + 2 * c;
      const double zi = own_pv[idx] - f_now[idx];
      e[c] = leader_weight_ > 0.0 ? leader_weight_ * (zi - leader_pv[idx]) : 0.0;
      for (int j = 0; j < m; ++j) {
        e[c] += weights_[j] * (zi - (neighbour_pv[4 * j + idx] - neighbour_f_now[6 * j + idx]));
      }
    }
    const double s = k.k1 * e[0] + k.k2 * e[1];  // s_i = K e_i, eq. (17)
    sliding_[axis] = s;
    const double sign = SwitchingSign(s, params_.sign, params_.boundary_layer);
    const double reaching = (params_.q * T - 1.0) * s + params_.eps * T * sign;  // eq. (48)
    rhs_[axis] = -reaching / kb_;
    if (leader_weight_ > 0.0) {
      const double y0 =
          k.k1 * (leader_pv[axis] + T * leader_pv[2 + axis]) + k.k2 * leader_pv[2 + axis];
      rhs_[axis] += leader_weight_ * ((mu1 - mu2 * sign) + y0 / kb_);  // a_i0 u0~_i, eq. (48)
    }
    own_y_[axis] = Y(k, T, own_pv, f_next, axis);
    for (int j = 0; j < m; ++j) {
      neighbour_y_[2 * j + axis] = Y(k, T, neighbour_pv + 4 * j, neighbour_f_next + 6 * j, axis);
    }
  }
}

void DiscreteSmcAgent::Solve(const double* w_neighbours) {
  for (int axis = 0; axis < 2; ++axis) {
    double sum = rhs_[axis];
    for (int j = 0; j < n_neighbours(); ++j) sum += weights_[j] * w_neighbours[2 * j + axis];
    w_[axis] = sum / degree_;                             // row i of L_H W = R
    acceleration_[axis] = w_[axis] - own_y_[axis] / kb_;  // u_i = w_i - y_i / KB
  }
}

void DiscreteSmcAgent::UseSolved(const double* w_own) {
  for (int axis = 0; axis < 2; ++axis) {
    w_[axis] = w_own[axis];
    acceleration_[axis] = w_[axis] - own_y_[axis] / kb_;
  }
}

double DiscreteSmcAgent::delta() const {
  const DiscreteSmcParams& p = params_;
  const double spread = leader_weight_ * kb_ * (p.u_max - p.u_min);
  const double delta1 = (p.eps * p.period + spread + p.eta0) / (2.0 - p.q * p.period);  // (49)
  const double delta2 = p.eps * p.period + spread;                                      // (50)
  return std::max(delta1, delta2);
}

double JacobiSpectralRadius(const Graph& graph) {
  const int n = graph.num_followers();
  auto row_scale = [&](int i) { return 1.0 / (graph.in_degree(i) + graph.leader_weight(i)); };
  if (n <= 400) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      for (int k = graph.in_begin(i); k < graph.in_end(i); ++k) {
        m(i, graph.in_neighbor(k)) += graph.in_weight(k) * row_scale(i);
      }
    }
    return m.eigenvalues().cwiseAbs().maxCoeff();
  }
  std::vector<double> x(n, 1.0), y(n);
  double root = 0.0;
  for (int it = 0; it < 20000; ++it) {
    double norm = 0.0;
    for (int i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int k = graph.in_begin(i); k < graph.in_end(i); ++k) {
        sum += graph.in_weight(k) * x[graph.in_neighbor(k)];
      }
      y[i] = 0.5 * (x[i] + sum * row_scale(i));
      norm = std::max(norm, y[i]);
    }
    if (norm == 0.0) return 0.0;
    const double previous = root;
    root = norm / *std::max_element(x.begin(), x.end());
    for (int i = 0; i < n; ++i) x[i] = y[i] / norm;
    if (it > 100 && std::abs(root - previous) < 1e-13) break;
  }
  return 2.0 * root - 1.0;
}

}  // namespace mjf::formation
