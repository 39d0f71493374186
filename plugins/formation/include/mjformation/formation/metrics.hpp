// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#ifndef MJFORMATION_FORMATION_METRICS_HPP_
#define MJFORMATION_FORMATION_METRICS_HPP_

namespace mjf::formation {

// eq. (68): sigma_f = || X - F - 1_N (x) x_0 || over positions and velocities of both axes of
// all followers. follower_pv: 4n (px, py, vx, vy); leader_pv: (px, py, vx, vy); shape_now: 6n
// from Shape::Evaluate. Units: a mix of m and m/s, as in the paper.
double FormationError(int n_followers, const double* follower_pv, const double* leader_pv,
                      const double* shape_now);

}  // namespace mjf::formation

#endif  // MJFORMATION_FORMATION_METRICS_HPP_
