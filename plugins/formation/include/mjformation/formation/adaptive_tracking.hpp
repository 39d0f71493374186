// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Distributed adaptive tracking of a leader whose input is bounded by an UNKNOWN bound:
// Z. Li, X. Liu, W. Ren and L. Xie, "Distributed tracking control for linear multiagent systems
// with a leader of bounded unknown input", IEEE Transactions on Automatic Control
// 58(2):518-523, 2013. The paper could not be read here; implemented from its common statement
// for agents x_i' = A x_i + B u_i, leader x_0' = A x_0 + B r_0 with ||r_0|| <= gamma unknown:
//   xi_i = sum_j a_ij (x_i - x_j) + a_i0 (x_i - x_0),
//   u_i  = d_i K xi_i + d_i r(K xi_i),
//   d_i' = tau [ -phi d_i + xi_i' Gamma xi_i + ||K xi_i|| ],   d_i(0) = d0 > 0,
//   K = -B' P^-1, Gamma = P^-1 B B' P^-1, P > 0 with A P + P A' - 2 B B' < 0,
// r(w) = w / ||w|| (the discontinuous law, phi = 0: xi -> 0, d_i converges) or its continuous
// version r(w) = w / (||w|| + kappa) with phi > 0 (xi and d_i uniformly ultimately bounded).
// Here A = [[0, 1], [0, 0]] (x) I_2, B = [0; 1] (x) I_2 (double integrator, both horizontal axes
// as one agent, so ||.|| is the norm over x and y and there is one d_i per follower); with the
// formation shift xi_i is (e_ip, e_iv) of eq. (16). P^-1 = Q from the Riccati equation
// A'Q + QA - QBB'Q + I = 0, which meets the LMI (Q(AP + PA' - 2BB')Q = -I - QBB'Q < 0):
// Q = [[sqrt 3, 1], [1, sqrt 3]], so K xi_i = -(e_ip + sqrt(3) e_iv) per axis and
// xi' Gamma xi = ||K xi||^2. Per axis: u_i = f_ia + d_i w_i + d_i w_i / (||w_i|| + kappa),
// w_i = K xi_i. sliding()[2i + axis] = -w_i = e_ip + sqrt(3) e_iv.
#ifndef MJFORMATION_FORMATION_ADAPTIVE_TRACKING_HPP_
#define MJFORMATION_FORMATION_ADAPTIVE_TRACKING_HPP_

#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

// sqrt 3: Q = [[sqrt 3, 1], [1, sqrt 3]] above, so K xi_i = -(e_ip + sqrt(3) e_iv).
inline constexpr double kAdaptiveVelocityWeight = 1.7320508075688772;

// Gains are defaults, NOT tuned.
struct AdaptiveTrackingParams {
  double tau = 0.02;   // 'tau', adaptation rate
  double phi = 0.05;   // 'phi', 1/s: leakage (sigma-modification), >= 0; 0 with kappa = 0 is
                       // the discontinuous law
  double kappa = 0.1;  // 'kappa', m/s^2: width of the continuous r(.), >= 0
  double d0 = 1.0;     // 'd0', initial gain d_i(0) > 0
  void Validate() const;
};

class AdaptiveTracking {
 public:
  AdaptiveTracking(const Graph& graph, const AdaptiveTrackingParams& params);
  // Evaluates u at `time` (s) with the current d_i, then advances d_i over the time since the
  // previous call.
  void Update(const FormationInput& input, double time);
  void Reset();  // d_i = d0, clock as before the first Update
  const std::vector<double>& acceleration() const { return acceleration_; }  // [2i + axis]
  const std::vector<double>& sliding() const { return sliding_; }
  const std::vector<double>& error() const { return error_; }
  const std::vector<double>& gain() const { return d_; }  // d_i, [i]
  double max_gain() const { return max_gain_; }           // largest d_i so far (since Reset)
  const Graph& graph() const { return graph_; }
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(d_);
    clock_.VisitState(visit);
    visit(max_gain_);
  }

 private:
  Graph graph_;
  AdaptiveTrackingParams params_;
  std::vector<double> acceleration_, sliding_, error_, unused_sliding_, d_;
  StepClock clock_;
  double max_gain_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_ADAPTIVE_TRACKING_HPP_
