// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// One follower's share of the discrete sliding-mode protocol (48), for distributed execution:
// everything follower i computes from its own state, its in-neighbours' states and (when
// a_i0 > 0) the leader's, with the u_j(k) coupling of (48) closed by the caller.
//
// (48) row i, multiplied out, is row i of L_H W = R in the coupling variable
//   w_i = u_i + y_i / KB,   y_i = k1 (p_i + T v_i) + k2 v_i - k1 f_ip(k+1) - k2 f_iv(k+1),
//   R_i = a_i0 (u0~_i + y_0 / KB) - ((qT - 1) s_i + eps T sgn(s_i)) / KB,
// with absolute positions p_i (so that a follower without a leader link never needs x_0) and
// y_0 = k1 (p_0 + T v_0) + k2 v_0. Hence w_i = (R_i + sum_j a_ij w_j) / (d_i + a_i0): a Jacobi
// row, exact when the w_j are the solution, and the compact form (53) solves all rows at once.
#ifndef MJFORMATION_FORMATION_DISCRETE_SMC_AGENT_HPP_
#define MJFORMATION_FORMATION_DISCRETE_SMC_AGENT_HPP_

#include <mjformation/formation/discrete_smc.hpp>
#include <vector>

namespace mjf::formation {

class DiscreteSmcAgent {
 public:
  // weights: a_ij of the in-neighbours, in the order the caller passes their data.
  DiscreteSmcAgent(const DiscreteSmcParams& params, double leader_weight,
                   std::vector<double> weights);

  // Sample k. own_pv / leader_pv / neighbour_pv[4m]: px, py, vx, vy (leader_pv may be null
  // when a_i0 = 0); f_now / f_next: [6] this follower's shape at t and t + T;
  // neighbour_f_now[6m]: theirs at t, neighbour_f_next[6m] at t + T.
  void Prepare(const double* own_pv, const double* leader_pv, const double* f_now,
               const double* f_next, const double* neighbour_pv, const double* neighbour_f_now,
               const double* neighbour_f_next);
  // w_j of neighbour m from its input u_j (last received: one sample old in (48)).
  double CouplingFromInput(int m, int axis, double u_j) const {
    return u_j + neighbour_y_[2 * m + axis] / kb_;
  }
  // One Jacobi row: w_i = (R_i + sum_j a_ij w_j) / (d_i + a_i0); w_neighbours[2m + axis].
  void Solve(const double* w_neighbours);
  // The exact w_i from a central solve of L_H W = R.
  void UseSolved(const double* w_own);

  const double* acceleration() const { return acceleration_; }  // u_i, [axis]
  const double* sliding() const { return sliding_; }            // s_i, [axis]
  const double* coupling() const { return w_; }                 // w_i, [axis]
  const double* rhs() const { return rhs_; }                    // R_i, [axis]
  int n_neighbours() const { return static_cast<int>(weights_.size()); }
  // Theorem 2's band for this follower, eqs. (49)-(50): the same as DiscreteSmc::delta(i).
  double delta() const;
  const DiscreteSmcParams& params() const { return params_; }

  // The held sample and what the next one reads of it (plugin_state.hpp).
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(neighbour_y_, own_y_, rhs_, w_, acceleration_, sliding_);
  }

 private:
  DiscreteSmcParams params_;
  double leader_weight_;
  std::vector<double> weights_;
  double degree_;                    // d_i + a_i0
  double kb_;                        // KB = k2 T, model (40)
  std::vector<double> neighbour_y_;  // [2m + axis]
  double own_y_[2] = {0, 0};
  double rhs_[2] = {0, 0}, w_[2] = {0, 0}, acceleration_[2] = {0, 0}, sliding_[2] = {0, 0};
};

// The convergence condition of Jacobi exchange on L_H = (D + H) - A: the iteration
// w <- (D + H)^-1 (A w + R) converges for every R iff rho((D + H)^-1 A) < 1. Exact (dense
// eigenvalues) for N <= 400; above, power iteration on the nonnegative (M + I) / 2, whose Perron
// root is (rho + 1) / 2 (a lower bound that converges to rho).
double JacobiSpectralRadius(const Graph& graph);

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_DISCRETE_SMC_AGENT_HPP_
