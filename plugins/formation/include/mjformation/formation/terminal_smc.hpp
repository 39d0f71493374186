// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Nonsingular terminal sliding-mode formation tracking: Y. Feng, X. Yu and Z. Man,
// "Non-singular terminal sliding mode control of rigid manipulators", Automatica
// 38(12):2159-2167, 2002. The paper could not be read here; implemented from its common
// statement for x1' = x2, x2' = f + g u + d, |d| <= l:
//   s   = x1 + (1/beta) x2^(p/q),     beta > 0, p > q > 0 odd, 1 < p/q < 2,
//   u   = -g^-1 [ f + beta (q/p) x2^(2 - p/q) + (l + eta) sgn(s) ],   eta > 0,
// giving s s' = (p/(q beta)) x2^(p/q - 1) (d s - (l + eta)|s|) <= -(p/(q beta)) x2^(p/q-1) eta |s|:
// s reaches 0 in finite time (x2 = 0 off s = 0 is not an attractor), and on s = 0,
// x1' = -beta^(q/p) x1^(q/p) reaches x1 = 0 within
//   t_s = p / (beta^(q/p) (p - q)) |x1(t_r)|^(1 - q/p)          (the stated sliding-phase time).
// No term is singular: x2^(2 - p/q) has a positive exponent, unlike the conventional TSM's
// x1^(q/p - 1) x2 term. x^(p/q) of odd p, q is sgn(x)|x|^(p/q); x^(p/q - 1) = |x|^(p/q - 1).
// On the formation, per axis (OUR ADAPTATION): x1 = e_ip, x2 = e_iv of eq. (16), whose
// dynamics are e_iv' = (L_H (U - F_a))_i - a_i0 u_0, so f = 0, g = 1, d = -a_i0 u_0 for the
// virtual input nu = L_H (U - F_a), and U = F_a + L_H^-1 nu with
//   nu_i = -beta (q/p) e_iv^(2 - p/q) - rho sgn(s_i),   rho = l + eta > a_i0 max|u_0|,
// one solve for both axes (a swarm-wide solve, like the paper's continuous law).
// sliding()[2i + axis] = s_i above (not s_i = K e_i of eq. (17)).
#ifndef MJFORMATION_FORMATION_TERMINAL_SMC_HPP_
#define MJFORMATION_FORMATION_TERMINAL_SMC_HPP_

#include <Eigen/Core>
#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/laplacian_solver.hpp>
#include <mjformation/formation/sliding.hpp>
#include <mjformation/formation/solved_law.hpp>
#include <vector>

namespace mjf::formation {

// Gains are defaults, NOT tuned.
struct TerminalSmcParams {
  double beta = 1.0;  // 'beta'
  int p = 5;          // 'p', odd, q < p < 2q (Feng et al.'s example uses 5/3)
  int q = 3;          // 'q', odd
  double rho = 1.5;   // 'rho' = l + eta, m/s^2 (switching gain)
  SignFunction sign = SignFunction::kSgn;
  double boundary_layer = 0.1;  // phi of sat (sign = sat only)
  void Validate() const;
};

// Feng et al.'s sliding-phase time from x1(t_r) = x1 on s = 0.
double TerminalSlidingTime(const TerminalSmcParams& params, double x1);

class TerminalSmc : public SolvedLaw {
 public:
  TerminalSmc(const Graph& graph, const TerminalSmcParams& params);
  void Update(const FormationInput& input);  // shape_now needed; no heap allocation
  // acceleration(), sliding() (s_i of the NTSM surface), error(): SolvedLaw's.
  template <typename Visit>
  void VisitState(Visit&) {}  // stateless

 private:
  TerminalSmcParams params_;
  std::vector<double> unused_sliding_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_TERMINAL_SMC_HPP_
