// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/realism/dryden.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mjf::realism {
namespace {

// integral_0^T s^n e^{-2 s / tau} ds for n = 0, 1, 2, as T^{n+1} f_n(x), x = 2 T / tau, with
// f_n(x) = integral_0^1 u^n e^{-x u} du: a series for small x (the closed forms cancel there).
double MomentIntegral(int n, double T, double tau) {
  const double x = 2 * T / tau;
  double f = 0;
  if (x < 0.5) {
    double term = 1;  // (-x)^k / k!
    for (int k = 0; k < 30; ++k) {
      f += term / (n + k + 1);
      term *= -x / (k + 1);
    }
  } else {
    const double e = std::exp(-x);
    if (n == 0) f = (1 - e) / x;
    if (n == 1) f = (1 - e * (1 + x)) / (x * x);
    if (n == 2) f = (2 - e * (2 + 2 * x + x * x)) / (x * x * x);
  }
  return std::pow(T, n + 1) * f;
}

}  // namespace

DrydenTurbulence::Second DrydenTurbulence::MakeSecond(double sigma, double tau, double T,
                                                      Gaussian& normal) {
  Second f;
  f.decay = std::exp(-T / tau);
  f.lag = T;
  // Discrete noise covariance Q = integral_0^T e^{A s} B B^T e^{A^T s} ds with
  // e^{A s} B = e^{-s/tau} [1, s]: Q = [[I0, I1], [I1, I2]].
  const double i0 = MomentIntegral(0, T, tau), i1 = MomentIntegral(1, T, tau),
               i2 = MomentIntegral(2, T, tau);
  f.l11 = std::sqrt(i0);
  f.l21 = i1 / f.l11;
  f.l22 = std::sqrt(std::max(0.0, i2 - f.l21 * f.l21));
  const double g = sigma / std::sqrt(tau);
  f.c1 = g * std::sqrt(3.0);
  f.c2 = g * (1 - std::sqrt(3.0)) / tau;
  // Stationary covariance P (A P + P A^T + B B^T = 0): P11 = tau/2, P12 = tau^2/4,
  // P22 = tau^3/4; the initial state is drawn from it.
  const double p11 = tau / 2, p12 = tau * tau / 4, p22 = tau * tau * tau / 4;
  const double a = std::sqrt(p11), b = p12 / a, c = std::sqrt(p22 - b * b);
  const double n1 = normal.Next(), n2 = normal.Next();
  f.x1 = a * n1;
  f.x2 = b * n1 + c * n2;
  return f;
}

DrydenTurbulence::DrydenTurbulence(const DrydenParams& p, double timestep, uint64_t seed)
    : normal_(seed) {
  for (int k = 0; k < 3; ++k) {
    if (!(p.sigma[k] >= 0) || !(p.scale_length[k] > 0) || !(p.airspeed > 0)) {
      throw std::invalid_argument("Dryden turbulence needs sigma >= 0, L > 0 and V > 0");
    }
  }
  const double tau_u = p.scale_length[0] / p.airspeed;
  phi_u_ = std::exp(-timestep / tau_u);
  noise_u_ = p.sigma[0] * std::sqrt(1 - phi_u_ * phi_u_);
  x_u_ = p.sigma[0] * normal_.Next();
  v_ = MakeSecond(p.sigma[1], p.scale_length[1] / p.airspeed, timestep, normal_);
  w_ = MakeSecond(p.sigma[2], p.scale_length[2] / p.airspeed, timestep, normal_);
}

double DrydenTurbulence::StepSecond(Second& f) {
  const double y = f.c1 * f.x1 + f.c2 * f.x2;
  const double n1 = normal_.Next(), n2 = normal_.Next();
  const double x1 = f.decay * f.x1 + f.l11 * n1;
  const double x2 = f.decay * (f.lag * f.x1 + f.x2) + f.l21 * n1 + f.l22 * n2;
  f.x1 = x1;
  f.x2 = x2;
  return y;
}

std::array<double, 3> DrydenTurbulence::Step() {
  const std::array<double, 3> out = {x_u_, StepSecond(v_), StepSecond(w_)};
  x_u_ = phi_u_ * x_u_ + noise_u_ * normal_.Next();
  return out;
}

}  // namespace mjf::realism
