// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/dryden_params.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mjf::realism {
namespace {

constexpr double kFoot = 0.3048;  // m

}  // namespace

DrydenParams DrydenParams::LowAltitude(double altitude_m, double w20_mps, double airspeed_mps) {
  const double h = altitude_m / kFoot;  // ft
  if (!(h >= 10 && h <= 1000)) {
    throw std::invalid_argument(
        "the Dryden low-altitude model holds for 10..1000 ft (3.05..304.8 "
        "m); altitude " +
        std::to_string(altitude_m) + " m is outside");
  }
  if (!(w20_mps >= 0) || !std::isfinite(w20_mps)) {
    throw std::invalid_argument("W20 must be a finite speed >= 0 m/s");
  }
  DrydenParams p;
  const double k = 0.177 + 0.000823 * h;
  const double lu = h / std::pow(k, 1.2) * kFoot;  // MIL-F-8785C fig. 10, low altitude
  p.scale_length = {lu, lu, altitude_m};
  const double sigma_w = 0.1 * w20_mps;  // MIL-F-8785C fig. 11
  const double sigma_uv = sigma_w / std::pow(k, 0.4);
  p.sigma = {sigma_uv, sigma_uv, sigma_w};
  p.airspeed = airspeed_mps;
  return p;
}

double DrydenParams::TwoSidedPsd(int k, double omega) const {
  const double L = scale_length[k], V = airspeed, s2 = sigma[k] * sigma[k];
  const double r = L * omega / V;
  if (k == 0) return s2 * (2 * L / V) / (1 + r * r);
  return s2 * (L / V) * (1 + 3 * r * r) / ((1 + r * r) * (1 + r * r));
}

}  // namespace mjf::realism
