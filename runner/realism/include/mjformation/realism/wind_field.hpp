// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The wind each vehicle feels: a uniform mean wind, Dryden turbulence (an independent seeded
// realisation per vehicle, rotated from the mean wind's axes into the world frame) and discrete
// 1-cosine gusts that hit every vehicle at the same time.
#ifndef MJFORMATION_REALISM_WIND_FIELD_HPP_
#define MJFORMATION_REALISM_WIND_FIELD_HPP_

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "mjformation/realism/dryden.hpp"
#include "mjformation/realism/gust.hpp"
#include "mjformation/realism/wind_params.hpp"

namespace mjf::realism {

class WindField {
 public:
  WindField(const WindParams& params, int n_vehicles, double timestep, uint64_t seed);

  // Advances to physics step `step` (0, 1, 2, ...; time = step * timestep) and returns the wind
  // velocity (m/s, world frame) at each vehicle.
  const std::vector<std::array<double, 3>>& Update(int64_t step);

  // The rotation of the turbulence's (u, v, w) axes into the world: u along the horizontal mean
  // wind (world x when calm), v horizontal to its left, w up.
  const std::array<double, 2>& along() const { return along_; }
  // The held samples, the turbulence filters and the last wind, both ways (checkpoints); the
  // gusts are functions of the step.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(gust_uvw_, turbulence_, shared_uvw_, wind_);
  }

 private:
  WindParams params_;
  double timestep_;
  int64_t turbulence_period_ = 1;  // steps between turbulence samples
  std::array<double, 2> along_;
  std::vector<std::array<double, 3>> gust_uvw_;  // the held turbulence sample per vehicle
  std::vector<DrydenTurbulence> turbulence_;     // per vehicle, then the shared one if rho > 0
  std::array<double, 3> shared_uvw_{};
  std::vector<std::array<double, 3>> wind_;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_WIND_FIELD_HPP_
