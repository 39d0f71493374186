// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The parameters of the wind field (wind_field.hpp): mean wind, Dryden turbulence and its
// correlation between vehicles, 1-cosine gusts. Plain data, so the experiment's struct carries
// them without the field.
#ifndef MJFORMATION_REALISM_WIND_PARAMS_HPP_
#define MJFORMATION_REALISM_WIND_PARAMS_HPP_

#include <array>
#include <vector>

#include "mjformation/realism/dryden_params.hpp"
#include "mjformation/realism/gust.hpp"

namespace mjf::realism {

struct WindParams {
  std::array<double, 3> mean{};  // m/s, world frame
  bool turbulence = false;
  DrydenParams dryden;  // used when turbulence
  // Turbulence samples per second, held in between (the shaping filters are discretised exactly
  // at this rate). Dryden spectra at these altitudes fall off above ~1 rad/s, so 100 Hz loses
  // nothing a vehicle responds to and costs a tenth of updating every 1 ms step.
  double turbulence_rate_hz = 100.0;
  // Correlation rho in [0, 1] of the turbulence between any two vehicles: each vehicle's is
  // sqrt(rho) x a shared realisation + sqrt(1 - rho) x its own (same spectrum, same variance).
  // 0: independent (an upper bound on the differential disturbance); 1: one field for all.
  // For vehicles a distance d apart, exp(-d / L_u) is the along-wind correlation of the model.
  double turbulence_correlation = 0.0;
  std::vector<OneCosineGust> gusts;

  bool IsCalm() const;  // no mean, no turbulence, no gusts
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_WIND_PARAMS_HPP_
