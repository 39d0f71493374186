// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Dryden turbulence after MIL-F-8785C (section 3.7.2) / MIL-HDBK-1797: three gust velocity
// components u (along the mean wind), v (across it, horizontal) and w (vertical), each white
// noise through the Dryden shaping filter, discretised exactly (the discrete sequence has the
// continuous process's autocorrelation at the sample times).
#ifndef MJFORMATION_REALISM_DRYDEN_HPP_
#define MJFORMATION_REALISM_DRYDEN_HPP_

#include <array>
#include <cstdint>

#include "mjformation/realism/dryden_params.hpp"
#include "mjformation/realism/gaussian.hpp"

namespace mjf::realism {

class DrydenTurbulence {
 public:
  // timestep: s between Step() calls. Starts in the stationary distribution (no transient).
  DrydenTurbulence(const DrydenParams& params, double timestep, uint64_t seed);

  // The gust velocity (u, v, w) in m/s now; then advances one timestep.
  std::array<double, 3> Step();
  // The filters' states and the noise stream, both ways (checkpoints); the coefficients are
  // fixed by the constructor.
  template <typename Archive>
  void VisitState(Archive& a) {
    a(x_u_, v_.x1, v_.x2, w_.x1, w_.x2, normal_);
  }

 private:
  // u: x' = -x/tau + sigma sqrt(2/tau) eta (eta unit white noise), exact: x+ = e x + s n.
  double phi_u_ = 0, noise_u_ = 0, x_u_ = 0;
  // v, w: x1' = -x1/tau + eta, x2' = -x2/tau + x1, y = g (sqrt(3) x1 + (1 - sqrt(3)) x2 / tau),
  // g = sigma / sqrt(tau): transfer function sigma sqrt(tau) (1 + sqrt(3) tau s) / (1 + tau s)^2.
  struct Second {
    double decay = 0, lag = 0;         // discrete transition e^{-T/tau} [[1, 0], [T, 1]]
    double l11 = 0, l21 = 0, l22 = 0;  // Cholesky factor of the discrete noise covariance
    double c1 = 0, c2 = 0;             // output y = c1 x1 + c2 x2
    double x1 = 0, x2 = 0;
  };
  static Second MakeSecond(double sigma, double tau, double timestep, Gaussian& normal);
  double StepSecond(Second& f);

  Gaussian normal_;
  Second v_, w_;
};

}  // namespace mjf::realism

#endif  // MJFORMATION_REALISM_DRYDEN_HPP_
