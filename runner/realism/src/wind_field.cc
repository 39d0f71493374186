// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/wind_field.hpp"

#include <algorithm>
#include <cmath>

#include "mjformation/time_steps.hpp"

namespace mjf::realism {

WindField::WindField(const WindParams& params, int n_vehicles, double timestep, uint64_t seed)
    : params_(params), timestep_(timestep), wind_(n_vehicles) {
  const double horizontal = std::hypot(params.mean[0], params.mean[1]);
  along_ = horizontal > 0
               ? std::array<double, 2>{params.mean[0] / horizontal, params.mean[1] / horizontal}
               : std::array<double, 2>{1.0, 0.0};
  if (params.turbulence) {
    // Validated as a whole number of steps (>= 1).
    turbulence_period_ = NearestSteps(1.0 / params.turbulence_rate_hz, timestep);
    turbulence_.reserve(n_vehicles);
    for (int i = 0; i < n_vehicles; ++i) {
      turbulence_.emplace_back(params.dryden, turbulence_period_ * timestep,
                               StreamSeed(seed, i, /*stream=*/2));
    }
    if (params.turbulence_correlation > 0) {
      turbulence_.emplace_back(params.dryden, turbulence_period_ * timestep,
                               StreamSeed(seed, n_vehicles, /*stream=*/2));
    }
    gust_uvw_.assign(n_vehicles, {0, 0, 0});
  }
}

const std::vector<std::array<double, 3>>& WindField::Update(int64_t step) {
  const double t = step * timestep_;
  std::array<double, 3> common = params_.mean;
  for (const OneCosineGust& g : params_.gusts) {
    const auto v = g.Velocity(t);
    for (int k = 0; k < 3; ++k) common[k] += v[k];
  }
  const double rho = params_.turbulence_correlation;
  const bool sample = !turbulence_.empty() && step % turbulence_period_ == 0;
  if (sample && rho > 0) shared_uvw_ = turbulence_.back().Step();
  const double own = std::sqrt(1 - rho), shared = std::sqrt(rho);
  for (size_t i = 0; i < wind_.size(); ++i) {
    wind_[i] = common;
    if (turbulence_.empty()) continue;
    if (sample) {
      const auto mine = turbulence_[i].Step();
      for (int k = 0; k < 3; ++k) {
        gust_uvw_[i][k] = rho > 0 ? own * mine[k] + shared * shared_uvw_[k] : mine[k];
      }
    }
    const auto& uvw = gust_uvw_[i];
    wind_[i][0] += along_[0] * uvw[0] - along_[1] * uvw[1];
    wind_[i][1] += along_[1] * uvw[0] + along_[0] * uvw[1];
    wind_[i][2] += uvw[2];
  }
  return wind_;
}

}  // namespace mjf::realism
