// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/record/estimation_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mjformation/record/output.hpp"

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kEps = 1e-15;
constexpr int kMaxTerms = 1000000;  // the series needs O(sqrt(a)) terms near x = a

// exp(a ln x - x - ln Gamma(a)): the factor common to both forms of P(a, x).
double GammaPrefactor(double a, double x) { return std::exp(a * std::log(x) - x - std::lgamma(a)); }

// P(a, x) by its series, for x < a + 1 (Numerical Recipes 3rd ed., eq. 6.2.5).
double GammaPSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxTerms && std::abs(term) > std::abs(sum) * kEps; ++n) {
    term *= x / (a + n);
    sum += term;
  }
  return sum * GammaPrefactor(a, x);
}

// 1 - Q(a, x), Q by its continued fraction (modified Lentz), for x >= a + 1 (NR eq. 6.2.7).
double GammaPContinuedFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxTerms; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < kEps) break;
  }
  return 1.0 - GammaPrefactor(a, x) * h;
}

// The chi-square CDF with k degrees of freedom: P(k/2, x/2).
double ChiSquareCdf(double x, double k) {
  if (x <= 0) return 0.0;
  const double a = 0.5 * k, h = 0.5 * x;
  return h < a + 1.0 ? GammaPSeries(a, h) : GammaPContinuedFraction(a, h);
}

double ChiSquarePdf(double x, double k) {
  const double a = 0.5 * k;
  return std::exp((a - 1.0) * std::log(x) - 0.5 * x - a * std::log(2.0) - std::lgamma(a));
}

// The standard normal p-quantile (Acklam's rational approximation, relative error < 1.2e-9):
// only the starting point of the Newton iteration, so its accuracy does not limit the result.
double NormalQuantile(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  auto tail = [&](double q) {
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  };
  if (p < 0.02425) return tail(std::sqrt(-2.0 * std::log(p)));
  if (p > 1.0 - 0.02425) return -tail(std::sqrt(-2.0 * std::log(1.0 - p)));
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

}  // namespace

double ChiSquareQuantile(double p, double k) {
  if (!(p > 0 && p < 1 && k > 0)) return kNaN;
  // Wilson-Hilferty: (chi2 / k)^(1/3) is nearly normal with mean 1 - 2/(9k), variance 2/(9k).
  const double v = 2.0 / (9.0 * k);
  const double wh = k * std::pow(std::max(1.0 - v + NormalQuantile(p) * std::sqrt(v), 0.0), 3);
  // Bracket [lo, hi] with CDF(lo) <= p <= CDF(hi), then Newton steps kept inside it.
  double lo = 0.0, hi = std::max(wh, k) + 10.0 * std::sqrt(2.0 * k) + 10.0;
  while (ChiSquareCdf(hi, k) < p) hi *= 2.0;
  double x = wh > 0 ? std::min(wh, hi) : 0.5 * hi;
  for (int it = 0; it < 200; ++it) {
    const double f = ChiSquareCdf(x, k) - p;
    (f < 0 ? lo : hi) = x;
    const double pdf = ChiSquarePdf(x, k);
    double next = pdf > 0 ? x - f / pdf : kNaN;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // bisection when Newton leaves
    if (std::abs(next - x) <= 1e-12 * x || hi - lo <= 1e-12 * hi) return next;
    x = next;
  }
  return x;
}

std::array<double, 2> MeanNeesBand95(long samples, int dim) {
  if (samples <= 0 || dim <= 0) return {kNaN, kNaN};
  const double n = static_cast<double>(samples), dof = n * dim;
  return {ChiSquareQuantile(0.025, dof) / n, ChiSquareQuantile(0.975, dof) / n};
}

double Nees6(const double error[6], const double covariance[36]) {
  // P = L L^T (Cholesky-Banachiewicz), then y = L^-1 e: e^T P^-1 e = |y|^2.
  double l[6][6] = {};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j <= i; ++j) {
      double s = 0.5 * (covariance[6 * i + j] + covariance[6 * j + i]);  // symmetric part
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      if (i == j) {
        if (!(s > 0) || !std::isfinite(s)) return kNaN;
        l[i][i] = std::sqrt(s);
      } else {
        l[i][j] = s / l[j][j];
      }
    }
  }
  double nees = 0;
  double y[6];
  for (int i = 0; i < 6; ++i) {
    double s = error[i];
    for (int k = 0; k < i; ++k) s -= l[i][k] * y[k];
    y[i] = s / l[i][i];
    nees += y[i] * y[i];
  }
  return nees;
}

EstimationMetrics::EstimationMetrics(int n_vehicles)
    : sums_(n_vehicles),
      single_band_{ChiSquareQuantile(0.025, kDim), ChiSquareQuantile(0.975, kDim)} {}

void EstimationMetrics::Add(const std::vector<mjfEstimate>& estimates,
                            const std::vector<mjfVehicleState>& truth) {
  // A formation acts on positions relative to the leader and its neighbours: an error common
  // to all vehicles (e.g. the GNSS wander's common part) cancels there, so the error of
  // p_i - p_0 is recorded beside the absolute one.
  double leader_error[3];
  for (int k = 0; k < 3; ++k) leader_error[k] = estimates[0].state.pos[k] - truth[0].pos[k];
  for (size_t i = 0; i < sums_.size(); ++i) {
    const mjfVehicleState& e = estimates[i].state;
    double error[kDim];
    for (int k = 0; k < 3; ++k) {
      error[k] = e.pos[k] - truth[i].pos[k];
      error[3 + k] = e.vel[k] - truth[i].vel[k];
    }
    Sums& s = sums_[i];
    s.position_sq += error[0] * error[0] + error[1] * error[1] + error[2] * error[2];
    s.velocity_sq += error[3] * error[3] + error[4] * error[4] + error[5] * error[5];
    for (int k = 0; k < 3; ++k) s.relative_sq += std::pow(error[k] - leader_error[k], 2);
    ++s.samples;
    const double nees = Nees6(error, estimates[i].covariance);
    if (std::isfinite(nees)) {
      s.nees += nees;
      ++s.nees_samples;
      s.nees_in_band += nees >= single_band_[0] && nees <= single_band_[1];
    }
  }
}

namespace {

nlohmann::ordered_json Band(const std::array<double, 2>& b) {
  return nlohmann::ordered_json::array({JsonNumber(b[0]), JsonNumber(b[1])});
}

double Ratio(double sum, long count) { return count > 0 ? sum / count : kNaN; }

}  // namespace

EstimationMetrics::Sums& EstimationMetrics::Sums::operator+=(const Sums& o) {
  position_sq += o.position_sq;
  velocity_sq += o.velocity_sq;
  relative_sq += o.relative_sq;
  nees += o.nees;
  samples += o.samples;
  nees_samples += o.nees_samples;
  nees_in_band += o.nees_in_band;
  return *this;
}

nlohmann::ordered_json EstimationMetrics::SumsJson(const Sums& s, bool relative_to_leader) {
  nlohmann::ordered_json v;
  v["samples"] = s.samples;
  v["position_rms_m"] = JsonNumber(std::sqrt(Ratio(s.position_sq, s.samples)));
  v["velocity_rms_m_s"] = JsonNumber(std::sqrt(Ratio(s.velocity_sq, s.samples)));
  if (relative_to_leader) {
    v["position_rms_relative_to_leader_m"] = JsonNumber(std::sqrt(Ratio(s.relative_sq, s.samples)));
  }
  v["nees_mean"] = JsonNumber(Ratio(s.nees, s.nees_samples));
  v["nees_samples"] = s.nees_samples;
  v["nees_band_95"] = Band(MeanNeesBand95(s.nees_samples, kDim));
  v["nees_fraction_in_single_band"] =
      JsonNumber(Ratio(static_cast<double>(s.nees_in_band), s.nees_samples));
  return v;
}

nlohmann::ordered_json EstimationMetrics::Summary(
    const std::vector<std::array<double, 3>>& counts) const {
  using Json = nlohmann::ordered_json;
  Json vehicles = Json::array();
  Sums followers;  // pooled over vehicles 1..N: the formation's view
  for (size_t i = 0; i < sums_.size(); ++i) {
    Json v;
    v["vehicle"] = i;
    v.update(SumsJson(sums_[i], i > 0));
    if (i < counts.size()) {
      v["fused"] = JsonNumber(counts[i][0]);
      v["gated"] = JsonNumber(counts[i][1]);
      v["too_old"] = JsonNumber(counts[i][2]);
    }
    vehicles.push_back(v);
    if (i > 0) followers += sums_[i];
  }
  Json out;
  out["state_dim"] = kDim;
  out["nees_band_95_single"] = Band(single_band_);
  out["followers"] = SumsJson(followers, true);
  out["vehicles"] = vehicles;
  return out;
}

}  // namespace mjf::runner
