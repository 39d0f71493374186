// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Baseline: the standard consensus-based time-varying formation tracking law for double
// integrators (e.g. Ren & Beard's second-order consensus with a leader, shifted by f_i):
//   u_i = f_ia + sum_j a_ij [ -kp ((p_i - f_ip) - (p_j - f_jp)) - kv ((v_i - f_iv) - (v_j - f_jv))
//   ]
//        + a_i0 [ -kp (p_i - f_ip - p_0) - kv (v_i - f_iv - v_0) ],
// i.e. u_i = f_ia - kp e_ip - kv e_iv with e_i of eq. (16). The leader's acceleration is not
// used, so a manoeuvring leader leaves a steady tracking error. With a directed graph the loop
// is stable when kv^2 / kp exceeds a bound set by L_H's complex eigenvalues (none for trees).
#ifndef MJFORMATION_FORMATION_LINEAR_CONSENSUS_HPP_
#define MJFORMATION_FORMATION_LINEAR_CONSENSUS_HPP_

#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

struct LinearConsensusParams {
  double kp = 1.0;        // 'kp', 1/s^2
  double kv = 2.0;        // 'kv', 1/s
  void Validate() const;  // kp > 0, kv > 0
};

class LinearConsensus {
 public:
  LinearConsensus(const Graph& graph, const LinearConsensusParams& params);
  void Update(const FormationInput& input);  // shape_now needed; no heap allocation
  const std::vector<double>& acceleration() const { return acceleration_; }  // [2i + axis]
  const std::vector<double>& error() const { return error_; }                // [4i + k]
  const Graph& graph() const { return graph_; }

  template <typename Visit>
  void VisitState(Visit& visit) {  // the last outputs (plugin_state.hpp)
    visit(acceleration_, error_);
  }

 private:
  Graph graph_;
  LinearConsensusParams params_;
  std::vector<double> acceleration_, error_, unused_sliding_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_LINEAR_CONSENSUS_HPP_
