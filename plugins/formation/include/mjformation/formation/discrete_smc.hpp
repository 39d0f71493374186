// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Discrete sliding-mode formation tracking protocol, eq. (48), computed in its compact form
// eq. (53) with one solve against the factored L_H, and Theorem 2's band and bound (47).
#ifndef MJFORMATION_FORMATION_DISCRETE_SMC_HPP_
#define MJFORMATION_FORMATION_DISCRETE_SMC_HPP_

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

struct DiscreteSmcParams {
  SlidingGains gains;    // 'k'
  double eps = 0.05;     // 'eps', switching gain
  double q = 4.5;        // 'q', 1/s, exponential reaching
  double period = 0.05;  // 'period', T in s
  double u_min = -1.0;   // 'u_min', m/s^2
  double u_max = 1.0;    // 'u_max', m/s^2
  SignFunction sign = SignFunction::kSgn;
  double boundary_layer = 0.1;  // 'boundary_layer', phi of sat (sign = sat only)
  double eta0 = 1e-6;           // 'eta0', the small eta_0 > 0 of Delta_1, eq. (49)
  // Our addition to Algorithm 2: on model (40) the surface s_i = 0 gives
  // e_ip(k+1) = (1 - T k1/k2) e_ip(k), stable only when T k1/k2 < 2 (see README). Set false
  // only to reproduce the paper's conditions (tests do, to show the divergence).
  bool require_stable_surface = true;
  // Input-constrained reaching law (docs/DISCUSSION.md, eqs. (C0)-(C9)): the bound a_max on
  // each follower's horizontal acceleration norm, m/s^2. +infinity (the default) is the
  // paper's law (48), untouched. 'accel_limit'.
  double accel_limit = std::numeric_limits<double>::infinity();
  // beta of (C3)-(C4), m/s^2: the acceleration the constrained law spends on reaching (its
  // braking curve asks for half of it). 0 (the default) derives it each sample, per follower,
  // from the bound: what the leader's compensation and the slot leave of it, (C3).
  double reach_accel = 0.0;

  // Algorithm 2 / Theorem 2: k1, k2 > 0, eps > 0, q > 0, T > 0, 1 - qT > 0, u_min <= u_max,
  // eta0 > 0, phi > 0 (sat); and T k1 / k2 < 2 (require_stable_surface). Throws
  // std::invalid_argument naming the key and the condition.
  void Validate() const;
  // accel_limit: > 0 and either +infinity (the paper's law) or finite and above the leader's
  // own acceleration bound sqrt(2) max(|u_min|, |u_max|) (C0); reach_accel >= 0, finite.
  void ValidateAccelLimit() const;
};

class DiscreteSmc {
 public:
  // Validates params, requires a spanning tree and factors L_H (throws std::invalid_argument).
  DiscreteSmc(const Graph& graph, const DiscreteSmcParams& params);

  // Evaluates eq. (53) at sample k: input.shape_now = F(k) (at t), input.shape_next = F(k+1)
  // (at t + T). O(N + edges + nnz(factor)), no heap allocation.
  void Update(const FormationInput& input);

  const std::vector<double>& acceleration() const { return acceleration_; }  // [2i + axis]
  const std::vector<double>& sliding() const { return sliding_; }            // [2i + axis]
  const std::vector<double>& error() const { return error_; }                // [4i + k]
  // Input constraint (accel_limit finite): what the last sample did and the largest
  // unconstrained demand ||u_i|| of law (48) so far (max over followers and samples).
  struct ConstraintStats {
    long samples = 0;      // samples taken
    long paper = 0;        // samples where every follower kept law (48), (C7)
    long constrained = 0;  // follower-samples where (C8) replaced law (48)
    double peak_paper_demand = 0.0;
  };
  const ConstraintStats& constraint_stats() const { return stats_; }
  bool constrained() const { return std::isfinite(params_.accel_limit); }
  // ||L_H^-1||_inf = max_i (L_H^-1 1)_i (L_H^-1 >= 0 elementwise): how much a consensus
  // error can grow into a follower's own (reported).
  double norm_inf_inv_lh() const { return norm_inf_inv_lh_; }
  void ResetConstraintStats() { stats_ = ConstraintStats{}; }

  // Theorem 2, eqs. (49)-(50), for follower i (uses a_i0): Delta_i = max(Delta1_i, Delta2_i).
  double delta1(int i) const;
  double delta2(int i) const;
  double delta(int i) const;
  double delta() const;  // max over followers
  // eq. (47) as EQUATIONS.md reads it: ||L_H^-1|| sqrt(N) Delta / ((k1 + k2) sqrt(2)).
  double error_bound() const;
  // Our re-derivation (README): after reaching, with w = L_H^-1 S and L_H^-1 >= 0 elementwise
  // (M-matrix), |w_i| <= b_i = (L_H^-1 Delta)_i; on model (40) with a shape satisfying
  // f_ip(k+1) = f_ip(k) + T f_iv(k), the position deviation obeys
  // z_p(k+1) = (1 - a) z_p(k) + (T/k2) w(k), a = T k1/k2, so ultimately
  // |z_ip| <= P_i = (T/k2) b_i / (1 - |1 - a|), |z_iv| <= V_i = (b_i + k1 P_i) / k2 and
  // sigma_f <= sqrt(2 sum_i (P_i^2 + V_i^2)) (two axes). +infinity when a >= 2.
  // Factors L_H again: call at report time, not per step.
  double ultimate_error_bound() const;
  double norm_inv_lh() const { return solver_.InverseTwoNorm(); }
  const DiscreteSmcParams& params() const { return params_; }
  const Graph& graph() const { return graph_; }

  // The state a sample leaves for the next (plugin_state.hpp): the held u_i and s_i, e_i and the
  // constraint counts. The factor of L_H and the right-hand sides are fixed or scratch.
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(acceleration_, sliding_, error_);
    visit(stats_.samples, stats_.paper, stats_.constrained, stats_.peak_paper_demand);
  }

 private:
  // The input-constrained reaching law (discrete_smc_constrained.cc): replaces the
  // demand of (48) by (C7)-(C8) when it leaves the feasible disc.
  void InitAccelLimit();
  void ApplyAccelLimit(const FormationInput& input);
  void ConstrainedDemand(const FormationInput& input, int i, const double* compensation,
                         double* demand) const;

  Graph graph_;
  DiscreteSmcParams params_;
  LaplacianSolver solver_;
  std::vector<double> acceleration_, sliding_, error_;
  Eigen::Matrix<double, Eigen::Dynamic, 2> rhs_;
  Eigen::Matrix<double, Eigen::Dynamic, 2> constrained_rhs_;  // (C5), accel_limit only
  double norm_inf_inv_lh_ = 0.0;
  ConstraintStats stats_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_DISCRETE_SMC_HPP_
