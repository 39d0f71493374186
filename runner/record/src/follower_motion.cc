// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/follower_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjformation/record/output.hpp"

namespace mjf::runner {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

FollowerMotion::FollowerMotion(int n_followers, double t0, double t1)
    : n_(n_followers),
      n_spectra_(std::min(n_followers, kMaxSpectra)),
      bins_(static_cast<int>(std::lround((kMaxHz - kMinHz) / kStepHz)) + 1),
      t0_(t0),
      t1_(t1),
      phasor_(bins_),
      phasor_sum_(bins_),
      spectrum_(static_cast<size_t>(n_spectra_) * bins_ * 2),
      tilt_sq_sum_(n_followers),
      tilt_x_sum_(n_followers),
      tilt_y_sum_(n_followers),
      thrust_mean_(n_followers),
      thrust_m2_(n_followers) {}

void FollowerMotion::Begin(double t) {
  ++samples_;
  // Hann window over [t0, t1]: side lobes fall as 1/f^3, so the steady tilt turning at the
  // formation's rate (below 0.1 Hz) stays out of the 0.3-5 Hz band.
  const double span = t1_ - t0_;
  weight_ = span > 0 ? 0.5 * (1 - std::cos(2 * M_PI * std::clamp((t - t0_) / span, 0.0, 1.0))) : 1;
  weight_sum_ += weight_;
  // e^{-i 2 pi (f0 + b df) t} = e^{-i 2 pi f0 t} (e^{-i 2 pi df t})^b: two sin/cos per sample,
  // phases from t itself (no drift from sample to sample).
  const std::complex<double> first = std::polar(weight_, -2 * M_PI * kMinHz * t);
  const std::complex<double> step = std::polar(1.0, -2 * M_PI * kStepHz * t);
  // Real arithmetic: std::complex's operator* goes through __muldc3 (NaN handling) in GCC.
  double re = first.real(), im = first.imag();
  const double step_re = step.real(), step_im = step.imag();
  for (int b = 0; b < bins_; ++b) {
    phasor_[b] = {re, im};
    phasor_sum_[b] += phasor_[b];
    const double next_re = re * step_re - im * step_im;
    im = re * step_im + im * step_re;
    re = next_re;
  }
}

void FollowerMotion::Add(int i, const double q[4], double thrust) {
  // Horizontal part of body z in the world (third column of R): its length is sin(tilt), its
  // direction the tilt's; rocking shows as oscillation of both components.
  const double x = 2 * (q[1] * q[3] + q[0] * q[2]);
  const double y = 2 * (q[2] * q[3] - q[0] * q[1]);
  const double cos_tilt = std::clamp(1 - 2 * (q[1] * q[1] + q[2] * q[2]), -1.0, 1.0);
  const double tilt = std::acos(cos_tilt);
  tilt_sq_sum_[i] += tilt * tilt;
  tilt_x_sum_[i] += weight_ * x;
  tilt_y_sum_[i] += weight_ * y;
  std::complex<double>* s = &spectrum_[static_cast<size_t>(i) * bins_ * 2];
  for (int b = 0; b < (i < n_spectra_ ? bins_ : 0); ++b) {  // real x complex: no __muldc3
    s[2 * b] += phasor_[b] * x;
    s[2 * b + 1] += phasor_[b] * y;
  }
  const double delta = thrust - thrust_mean_[i];  // Welford: exact mean and variance online
  thrust_mean_[i] += delta / static_cast<double>(samples_);
  thrust_m2_[i] += delta * (thrust - thrust_mean_[i]);
}

double FollowerMotion::DominantHz(int i) const {
  if (samples_ == 0 || !(weight_sum_ > 0) || i >= n_spectra_) return kNaN;
  const double n = static_cast<double>(samples_);
  const double mx = tilt_x_sum_[i] / weight_sum_, my = tilt_y_sum_[i] / weight_sum_;
  const std::complex<double>* s = &spectrum_[static_cast<size_t>(i) * bins_ * 2];
  // Power of the (weighted-)mean-removed components: sum w (x - mx) e = sum w x e - mx sum w e.
  const auto power = [&](int b) {
    return std::norm(s[2 * b] - mx * phasor_sum_[b]) +
           std::norm(s[2 * b + 1] - my * phasor_sum_[b]);
  };
  int best = 0;
  double best_power = -1;
  for (int b = 0; b < bins_; ++b) {
    const double p = power(b);
    if (p > best_power) {
      best_power = p;
      best = b;
    }
  }
  if (!(best_power > 1e-12 * n * n)) return kNaN;  // no motion (e.g. a point mass)
  // Largest at the band's lower edge: the spectrum falls from below the band, no oscillation
  // peak inside it (the formation's own slow motion leaking in).
  if (best == 0) return kNaN;
  double offset = 0;  // vertex of the parabola through the peak and its neighbours, in bins
  if (best > 0 && best < bins_ - 1) {
    const double a = power(best - 1), c = power(best + 1);
    const double denominator = a - 2 * best_power + c;
    if (denominator < 0) offset = 0.5 * (a - c) / denominator;
  }
  return kMinHz + (best + offset) * kStepHz;
}

void FollowerMotion::AddTo(nlohmann::ordered_json* metrics) const {
  nlohmann::ordered_json tilt = nlohmann::ordered_json::array();
  nlohmann::ordered_json hz = nlohmann::ordered_json::array();
  nlohmann::ordered_json thrust = nlohmann::ordered_json::array();
  const double n = static_cast<double>(samples_);
  for (int i = 0; i < n_; ++i) {
    tilt.push_back(JsonNumber(samples_ ? std::sqrt(tilt_sq_sum_[i] / n) * 180 / M_PI : kNaN));
    hz.push_back(JsonNumber(DominantHz(i)));
    thrust.push_back(JsonNumber(samples_ ? std::sqrt(thrust_m2_[i] / n) : kNaN));
  }
  (*metrics)["rms_tilt_deg_in_window"] = tilt;
  (*metrics)["tilt_oscillation_hz_in_window"] = hz;
  (*metrics)["rms_thrust_variation_n_in_window"] = thrust;
}

double CollectiveForce(const double* ctrl, const mjfActuatorInfo* info, int n_actuators) {
  double f[3] = {0, 0, 0};
  for (int k = 0; k < n_actuators; ++k) {
    for (int j = 0; j < 3; ++j) f[j] += ctrl[k] * info[k].gear[j];
  }
  return std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
}

}  // namespace mjf::runner
