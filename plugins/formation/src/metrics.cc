// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <cmath>
#include <mjformation/formation/metrics.hpp>

namespace mjf::formation {

double FormationError(int n_followers, const double* follower_pv, const double* leader_pv,
                      const double* shape_now) {
  double sum = 0.0;
  for (int i = 0; i < n_followers; ++i) {
    for (int k = 0; k < 4; ++k) {  // px, py, vx, vy: shape components 0..3 share the layout
      const double deviation = follower_pv[4 * i + k] - shape_now[6 * i + k] - leader_pv[k];
      sum += deviation * deviation;  // eq. (68)
    }
  }
  return std::sqrt(sum);
}

}  // namespace mjf::formation
