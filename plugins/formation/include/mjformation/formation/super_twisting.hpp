// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Super-twisting (second-order sliding mode) formation tracking on the sliding variable
// s_i = K e_i of eq. (17) of Wang et al. (AST 2021). Sources: A. Levant, "Sliding order and
// sliding accuracy in sliding mode control", International Journal of Control 58(6):1247-1263,
// 1993 (the algorithm and its sufficient gain condition); J. A. Moreno and M. Osorio, "Strict
// Lyapunov functions for the super-twisting algorithm", IEEE Transactions on Automatic Control
// 57(4):1035-1040, 2012 (the quadratic Lyapunov function and the convergence-time bound). The
// papers could not be read here; implemented from their common statements:
//   STA:    x' = -lambda |x|^(1/2) sgn(x) + w + d(t),  w' = -alpha sgn(x),  |d'| <= C;
//   Levant: x = 0 is reached in finite time if alpha > C and lambda^2 >= 4 C (alpha + C) /
//           (alpha - C);
//   Moreno & Osorio (d = 0): with zeta = (|x|^(1/2) sgn x, w), V = zeta' P zeta,
//           A' P + P A = -Q, A = [[-lambda/2, 1/2], [-alpha, 0]], V' <= -g V^(1/2),
//           g = lambda_min(Q) lambda_min(P)^(1/2) / lambda_max(P), so x and w reach 0 within
//           T = 2 V(0)^(1/2) / g (here Q = I).
// On the formation (per axis, compact form like eq. (33)): s' = k1 E_v + k2 L_H (U - F_a) -
// k2 H 1 u_0, so choosing k2 L_H (U - F_a) = -k1 E_v + V with
//   V_i = -lambda |s_i|^(1/2) sgn(s_i) + w_i,  w_i' = -alpha sgn(s_i)
// gives s_i' = V_i + d_i with d_i = -k2 a_i0 u_0: the STA, perturbed by the leader's input, and
// C = k2 a_i0 max|u_0'| (the leader's jerk bound). Evaluated as U = F_a + L_H^-1 (V - k1 E_v)/k2
// with one solve (both axes), like the paper's continuous law (a swarm-wide solve).
#ifndef MJFORMATION_FORMATION_SUPER_TWISTING_HPP_
#define MJFORMATION_FORMATION_SUPER_TWISTING_HPP_

#include <Eigen/Core>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/sliding.hpp>
#include <mjformation/formation/solved_law.hpp>
#include <vector>

namespace mjf::formation {

// Gains are defaults, NOT tuned.
struct SuperTwistingParams {
  SlidingGains gains;     // 'k': K = [k1 k2] of eq. (17)
  double lambda = 1.5;    // 'lambda', (s-units)^(1/2)/s: the |s|^(1/2) gain
  double alpha = 0.5;     // 'alpha', (s-units)/s^2: the integral gain, > C
  void Validate() const;  // k1, k2, lambda, alpha > 0
};

// Moreno & Osorio's convergence-time bound for the unperturbed STA started at (s0, w0).
double SuperTwistingTimeBound(double lambda, double alpha, double s0, double w0);

// Levant's sufficient condition for a perturbation with |d'| <= c.
bool LevantConditionHolds(double lambda, double alpha, double c);

class SuperTwisting : public SolvedLaw {
 public:
  SuperTwisting(const Graph& graph, const SuperTwistingParams& params);
  // Evaluates u at `time` (s) and advances w_i over the time since the previous call.
  void Update(const FormationInput& input, double time);
  void Reset();  // w_i = 0, the clock and the bound as before the first Update
  // acceleration(), sliding() (s_i = K e_i), error(): SolvedLaw's.
  const std::vector<double>& integral() const { return w_; }  // w_i, [2i + axis]
  // max over i, axis of SuperTwistingTimeBound from the first Update's s_i (w_i = 0); < 0 before.
  double reaching_time_bound() const { return reaching_time_bound_; }
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(w_);
    clock_.VisitState(visit);
    visit(reaching_time_bound_);
  }

 private:
  SuperTwistingParams params_;
  std::vector<double> w_;
  StepClock clock_;
  double reaching_time_bound_ = -1.0;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_SUPER_TWISTING_HPP_
