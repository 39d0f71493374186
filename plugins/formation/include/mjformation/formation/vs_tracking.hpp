// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Variable-structure coordinated tracking for double integrators with a dynamic leader:
// Y. Cao and W. Ren, "Distributed coordinated tracking with reduced interaction via a variable
// structure approach", IEEE Transactions on Automatic Control 57(1):33-48, 2012, section IV
// (double-integrator dynamics). The paper could not be read here; the law is implemented from
// its common statement (e.g. as restated in later surveys of leader-follower tracking):
//   u_i = - sum_j a_ij [ (r_i - r_j) + alpha (v_i - v_j) ] - b_i [ (r_i - r_0) + alpha (v_i - v_0)
//   ]
//         - beta sgn{ sum_j a_ij [ gamma (r_i - r_j) + (v_i - v_j) ]
//                     + b_i [ gamma (r_i - r_0) + (v_i - v_0) ] },
// with a leader whose acceleration is bounded, |a_0| <= gamma_l, undirected follower graph, some
// b_i > 0; the tracking errors go to zero (globally exponentially) when beta > gamma_l and alpha,
// gamma satisfy the paper's conditions (gamma small enough against alpha and the eigenvalues of
// L + B). "Reduced interaction": only relative positions and velocities, no neighbour
// accelerations. With the formation shift (literature_laws.hpp) the neighbour sums are e_ip and
// e_iv of eq. (16) (a_i0 = b_i), so per axis:
//   u_i = f_ia - (e_ip + alpha e_iv) - beta sgn(gamma e_ip + e_iv).
// sliding()[2i + axis] is the switching variable gamma e_ip + e_iv.
#ifndef MJFORMATION_FORMATION_VS_TRACKING_HPP_
#define MJFORMATION_FORMATION_VS_TRACKING_HPP_

#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

// Gains are defaults, NOT tuned (the benchmark's one tuning procedure chooses them later).
struct VsTrackingParams {
  double alpha = 2.0;  // 'alpha', s: velocity weight of the linear term
  double beta = 1.5;   // 'beta', m/s^2: switching gain, > the leader's acceleration bound
  double gamma = 1.0;  // 'gamma', 1/s: position weight inside sgn
  SignFunction sign = SignFunction::kSgn;
  double boundary_layer = 0.1;  // phi of sat (sign = sat only), m/s
  void Validate() const;        // alpha, beta, gamma > 0; phi > 0 for sat
};

class VsTracking {
 public:
  VsTracking(const Graph& graph, const VsTrackingParams& params);
  void Update(const FormationInput& input);  // shape_now needed; no heap allocation
  const std::vector<double>& acceleration() const { return acceleration_; }  // [2i + axis]
  const std::vector<double>& sliding() const { return sliding_; }            // [2i + axis]
  const std::vector<double>& error() const { return error_; }                // [4i + k]
  const Graph& graph() const { return graph_; }
  template <typename Visit>
  void VisitState(Visit&) {}  // stateless: the output is a function of this step's input

 private:
  Graph graph_;
  VsTrackingParams params_;
  std::vector<double> acceleration_, sliding_, error_, unused_sliding_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_VS_TRACKING_HPP_
