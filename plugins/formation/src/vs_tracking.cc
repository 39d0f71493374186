// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <mjformation/formation/literature_laws.hpp>
#include <mjformation/formation/vs_tracking.hpp>

namespace mjf::formation {

void VsTrackingParams::Validate() const {
  RequirePositive(alpha, "alpha", "Cao & Ren (2012)'s double-integrator law");
  RequirePositive(beta, "beta", "Cao & Ren (2012)'s double-integrator law");
  RequirePositive(gamma, "gamma", "Cao & Ren (2012)'s double-integrator law");
  ValidateSign(sign, boundary_layer);
}

VsTracking::VsTracking(const Graph& graph, const VsTrackingParams& params)
    : graph_(WithSpanningTree(graph)),
      params_(Validated(params)),
      acceleration_(2 * graph_.num_followers(), 0.0),
      sliding_(2 * graph_.num_followers(), 0.0),
      error_(4 * graph_.num_followers(), 0.0),
      unused_sliding_(2 * graph_.num_followers(), 0.0) {}

void VsTracking::Update(const FormationInput& input) {
  // sum_j a_ij (x_i - x_j) + b_i (x_i - x_0) with the formation shift is e_i of eq. (16).
  ComputeErrorAndSliding(graph_, SlidingGains{}, input.leader_pv, input.follower_pv,
                         input.shape_now, error_.data(), unused_sliding_.data());
  for (int i = 0; i < graph_.num_followers(); ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const double ep = error_[4 * i + axis], ev = error_[4 * i + 2 + axis];
      const double sigma = params_.gamma * ep + ev;  // sum a_ij [gamma (r_i - r_j) + (v_i - v_j)]
      sliding_[2 * i + axis] = sigma;
      acceleration_[2 * i + axis] =
          input.shape_now[6 * i + 4 + axis]  // f_ia: the formation shift of u_i
          - (ep + params_.alpha * ev)        // - sum a_ij [(r_i - r_j) + alpha (v_i - v_j)]
          - params_.beta * SwitchingSign(sigma, params_.sign,
                                         params_.boundary_layer);  // - beta sgn{...}
    }
  }
}

}  // namespace mjf::formation
