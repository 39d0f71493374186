// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Observer-based tracking of an active leader whose velocity is not measured:
// Y. Hong, J. Hu and L. Gao, "Tracking control for multi-agent consensus with an active leader
// and variable topology", Automatica 42(7):1177-1182, 2006. The paper could not be read here;
// implemented from its common statement: first-order followers x_i' = u_i, a leader
// x_0' = v_0, v_0' = a_0, whose position (not velocity) its neighbours measure; each follower
// runs an estimate vbar_i of v_0:
//   u_i     = vbar_i - k [ sum_j a_ij (x_i - x_j) + b_i (x_i - x_0) ],
//   vbar_i' = a_0 - gamma k [ sum_j a_ij (x_i - x_j) + b_i (x_i - x_0) ],
// with k, gamma > 0 (the paper's conditions on k relative to the interconnection graph's
// eigenvalues apply to its switching topologies). With a_0 known, x_i -> x_0 and vbar_i -> v_0;
// with a_0 unknown (used here: a_0 is replaced by 0, the follower never sees the leader's
// acceleration) the errors stay bounded by a multiple of the bound of a_0.
// Our followers are double integrators, so (OUR ADAPTATION) the law's u_i becomes a velocity
// reference tracked by an inner loop with gain kv, feeding forward vbar_i' (known to the
// follower) and the formation shift; per axis, with e_ip of eq. (16) (b_i = a_i0):
//   v_ref   = f_iv + vbar_i - k e_ip,
//   vbar_i' = -gamma k e_ip,
//   u_i     = f_ia + vbar_i' + kv (v_ref - v_i).
// Nothing here uses the leader's velocity or acceleration. sliding()[2i + axis] = e_ip.
#ifndef MJFORMATION_FORMATION_OBSERVER_TRACKING_HPP_
#define MJFORMATION_FORMATION_OBSERVER_TRACKING_HPP_

#include <mjformation/formation/graph.hpp>
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/sliding.hpp>
#include <vector>

namespace mjf::formation {

// Gains are defaults, NOT tuned.
struct ObserverTrackingParams {
  double k = 1.0;         // 'k', 1/s: position consensus gain
  double gamma = 1.0;     // 'gamma', 1/s: estimator gain
  double kv = 4.0;        // 'kv', 1/s: inner velocity loop (our adaptation to double integrators)
  void Validate() const;  // all > 0
};

class ObserverTracking {
 public:
  ObserverTracking(const Graph& graph, const ObserverTrackingParams& params);
  // Evaluates u at `time` (s), then advances vbar_i over the time since the previous call.
  // input.leader_pv[2..3] (the leader's velocity) is not read.
  void Update(const FormationInput& input, double time);
  void Reset();  // vbar_i = 0, clock as before the first Update
  const std::vector<double>& acceleration() const { return acceleration_; }  // [2i + axis]
  const std::vector<double>& sliding() const { return sliding_; }            // e_ip
  const std::vector<double>& error() const { return error_; }
  const std::vector<double>& leader_velocity_estimate() const { return vbar_; }  // [2i + axis]
  const Graph& graph() const { return graph_; }
  template <typename Visit>
  void VisitState(Visit& visit) {
    visit(vbar_);
    clock_.VisitState(visit);
  }

 private:
  Graph graph_;
  ObserverTrackingParams params_;
  std::vector<double> acceleration_, sliding_, error_, unused_sliding_, vbar_;
  StepClock clock_;
};

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_OBSERVER_TRACKING_HPP_
