// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The parameters of Dryden turbulence (dryden.hpp): intensities, scale lengths and airspeed,
// with MIL-F-8785C's low-altitude model. Plain data, so the experiment's struct carries them
// without the shaping filters.
#ifndef MJFORMATION_REALISM_DRYDEN_PARAMS_HPP_
#define MJFORMATION_REALISM_DRYDEN_PARAMS_HPP_

#include <array>

namespace mjf::realism {

struct DrydenParams {
  std::array<double, 3> sigma{};         // m/s, intensity of u, v, w
  std::array<double, 3> scale_length{};  // m, L_u, L_v, L_w
  double airspeed = 1.0;                 // m/s, V: the speed the frozen field passes the vehicle

  // The low-altitude model (h < 1000 ft) of MIL-F-8785C, with h and L in feet there:
  //   L_w = h, L_u = L_v = h / (0.177 + 0.000823 h)^1.2,
  //   sigma_w = 0.1 W20, sigma_u = sigma_v = sigma_w / (0.177 + 0.000823 h)^0.4,
  // W20 the wind speed at 20 ft (light 15 kt = 7.7 m/s, moderate 30 kt = 15.4 m/s, severe 45 kt).
  // altitude in m (throws std::invalid_argument outside the model's 10..1000 ft), w20 in m/s.
  static DrydenParams LowAltitude(double altitude_m, double w20_mps, double airspeed_mps);

  // Two-sided power spectral density S(omega) (m^2/s^2 per rad/s) of component k, with
  // var = (1 / 2 pi) * integral over all omega. MIL-F-8785C's one-sided Phi(omega) = S / pi:
  //   u: Phi = sigma^2 (2 L / (pi V)) / (1 + (L omega / V)^2)
  //   v, w: Phi = sigma^2 (L / (pi V)) (1 + 3 (L omega / V)^2) / (1 + (L omega / V)^2)^2
  double TwoSidedPsd(int k, double omega) const;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_DRYDEN_PARAMS_HPP_
