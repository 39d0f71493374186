// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <algorithm>
#include <cmath>
#include <mjformation/formation/adaptive_tracking.hpp>
#include <sstream>
#include <stdexcept>

namespace mjf::formation {
namespace {

void RequireNonNegative(double value, const char* key) {
  if (!(value >= 0.0 && std::isfinite(value))) {
    std::ostringstream out;
    out << "attribute '" << key << "': " << key << " >= 0 is required (got " << value << ")";
    throw std::invalid_argument(out.str());
  }
}

}  // namespace

void AdaptiveTrackingParams::Validate() const {
  RequirePositive(tau, "tau", "Li, Liu, Ren & Xie (2013)'s adaptive law");
  RequirePositive(d0, "d0", "Li, Liu, Ren & Xie (2013)'s adaptive law");
  RequireNonNegative(phi, "phi");
  RequireNonNegative(kappa, "kappa");
}

AdaptiveTracking::AdaptiveTracking(const Graph& graph, const AdaptiveTrackingParams& params)
    : graph_(WithSpanningTree(graph)),
      params_(Validated(params)),
      acceleration_(2 * graph_.num_followers(), 0.0),
      sliding_(2 * graph_.num_followers(), 0.0),
      error_(4 * graph_.num_followers(), 0.0),
      unused_sliding_(2 * graph_.num_followers(), 0.0),
      d_(graph_.num_followers(), params_.d0),
      max_gain_(params_.d0) {}

void AdaptiveTracking::Reset() {
  std::fill(d_.begin(), d_.end(), params_.d0);
  clock_.Reset();
  max_gain_ = params_.d0;
}

void AdaptiveTracking::Update(const FormationInput& input, double time) {
  const double dt = clock_.Advance(time);
  ComputeErrorAndSliding(graph_, SlidingGains{}, input.leader_pv, input.follower_pv,
                         input.shape_now, error_.data(), unused_sliding_.data());  // xi_i
  for (int i = 0; i < graph_.num_followers(); ++i) {
    double w[2];
    for (int axis = 0; axis < 2; ++axis) {
      w[axis] =
          -(error_[4 * i + axis] + kAdaptiveVelocityWeight * error_[4 * i + 2 + axis]);  // K xi_i
      sliding_[2 * i + axis] = -w[axis];
    }
    const double norm = std::hypot(w[0], w[1]);  // ||K xi_i||
    const double d = d_[i];
    for (int axis = 0; axis < 2; ++axis) {
      // r(w) = w / (||w|| + kappa); r(0) = 0 for the discontinuous law (kappa = 0).
      const double r = norm + params_.kappa > 0.0 ? w[axis] / (norm + params_.kappa) : 0.0;
      acceleration_[2 * i + axis] = input.shape_now[6 * i + 4 + axis]  // f_ia (formation shift)
                                    + d * w[axis] + d * r;             // d_i K xi_i + d_i r(K xi_i)
    }
    // d_i' = tau [-phi d_i + xi' Gamma xi + ||K xi||], xi' Gamma xi = ||K xi||^2.
    d_[i] = d + dt * params_.tau * (-params_.phi * d + norm * norm + norm);
    max_gain_ = std::max(max_gain_, d_[i]);
  }
}

}  // namespace mjf::formation
