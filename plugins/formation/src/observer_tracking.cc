// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <mjformation/formation/observer_tracking.hpp>

namespace mjf::formation {

void ObserverTrackingParams::Validate() const {
  RequirePositive(k, "k", "Hong, Hu & Gao (2006)'s tracking law");
  RequirePositive(gamma, "gamma", "Hong, Hu & Gao (2006)'s estimator");
  RequirePositive(kv, "kv", "the inner velocity loop");
}

ObserverTracking::ObserverTracking(const Graph& graph, const ObserverTrackingParams& params)
    : graph_(WithSpanningTree(graph)),
      params_(Validated(params)),
      acceleration_(2 * graph_.num_followers(), 0.0),
      sliding_(2 * graph_.num_followers(), 0.0),
      error_(4 * graph_.num_followers(), 0.0),
      unused_sliding_(2 * graph_.num_followers(), 0.0),
      vbar_(2 * graph_.num_followers(), 0.0) {}

void ObserverTracking::Reset() {
  std::fill(vbar_.begin(), vbar_.end(), 0.0);
  clock_.Reset();
}

void ObserverTracking::Update(const FormationInput& input, double time) {
  const double dt = clock_.Advance(time);
  // Only the position rows of e_i are used: they do not involve the leader's velocity.
  ComputeErrorAndSliding(graph_, SlidingGains{}, input.leader_pv, input.follower_pv,
                         input.shape_now, error_.data(), unused_sliding_.data());
  for (int i = 0; i < graph_.num_followers(); ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const int j = 2 * i + axis;
      const double ep = error_[4 * i + axis];  // sum_j a_ij (x_i - x_j) + b_i (x_i - x_0)
      sliding_[j] = ep;
      const double vbar_rate = -params_.gamma * params_.k * ep;  // vbar_i' with a_0 -> 0
      const double v_ref = input.shape_now[6 * i + 2 + axis] + vbar_[j] - params_.k * ep;  // u_i
      acceleration_[j] = input.shape_now[6 * i + 4 + axis] + vbar_rate +
                         params_.kv * (v_ref - input.follower_pv[4 * i + 2 + axis]);
      vbar_[j] += dt * vbar_rate;
    }
  }
}

}  // namespace mjf::formation
