// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What every formation protocol shares: the input layout, the gains K = [k1, k2], the sign
// function (with an optional boundary layer) and the error/sliding variables of eqs. (16)-(17).
#ifndef MJFORMATION_FORMATION_SLIDING_HPP_
#define MJFORMATION_FORMATION_SLIDING_HPP_

#include <mjformation/formation/graph.hpp>
#include <string>

namespace mjf::formation {

// One evaluation's input; all pointers are borrowed for the duration of Update().
struct FormationInput {
  const double* leader_pv = nullptr;    // [4] px, py, vx, vy of the leader (m, m/s)
  const double* follower_pv = nullptr;  // [4n] px, py, vx, vy per follower
  const double* shape_now = nullptr;    // [6n] Shape::Evaluate at t
  const double* shape_next = nullptr;   // [6n] Shape::Evaluate at t + T (discrete SMC only)
};

// K = [k1, k2] of eq. (17); both > 0 (Theorem 1 / Theorem 2).
struct SlidingGains {
  double k1 = 3.0;
  double k2 = 1.0;
};

// sgn as printed, or sat(s / phi) with boundary-layer width phi (a deviation from the paper
// that trades the quasi-sliding band of Theorem 2 for a smooth command).
enum class SignFunction { kSgn, kSat };

// sgn(s) (sgn(0) = 0) or clamp(s / boundary_layer, -1, 1).
double SwitchingSign(double s, SignFunction function, double boundary_layer);

// "sgn" / "sat"; throws std::invalid_argument naming `key` otherwise.
SignFunction ParseSignFunction(const std::string& text, const char* key = "sign");

// Validation shared by the protocols; each throws std::invalid_argument naming the key.
void ValidateGains(const SlidingGains& gains);                    // 'k': k1, k2 > 0
void ValidateLeaderBounds(double u_min, double u_max);            // u_min <= u_max
void ValidateSign(SignFunction function, double boundary_layer);  // phi > 0 for sat

// eqs. (16)-(17) per horizontal axis: error[4i + k], k = (px, py, vx, vy), is e_i =
// sum_j a_ij (x_i - f_i - x_j + f_j) + a_i0 (x_i - f_i - x_0); sliding[2i + axis] = K e_i.
// Cost O(N + edges), no allocation.
void ComputeErrorAndSliding(const Graph& graph, const SlidingGains& gains, const double* leader_pv,
                            const double* follower_pv, const double* shape, double* error,
                            double* sliding);

// For constructors' member initializer lists: the argument, once it has passed its checks.
template <typename Params>
const Params& Validated(const Params& params) {
  params.Validate();  // throws std::invalid_argument naming the key and the condition
  return params;
}
inline const Graph& WithSpanningTree(const Graph& graph) {
  graph.RequireSpanningTree();  // Assumption 2
  return graph;
}

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_SLIDING_HPP_
