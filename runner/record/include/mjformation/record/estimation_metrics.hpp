// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// How good an estimator plugin's estimate was (summary.json "estimation"): per
// vehicle, over the metric window, the RMS position and velocity error against the truth and
// the normalised estimation error squared (NEES) of the 6-dimensional (p, v) estimate, with the
// chi-square 95 % bands it is judged against. Plain arrays, no MuJoCo: tested alone.
#ifndef MJFORMATION_RECORD_ESTIMATION_METRICS_HPP_
#define MJFORMATION_RECORD_ESTIMATION_METRICS_HPP_

#include <mjformation/plugin.h>

#include <array>
#include <nlohmann/json.hpp>
#include <vector>

namespace mjf::runner {

// The p-quantile of the chi-square distribution with k degrees of freedom (0 < p < 1, k > 0):
// the x with P(k/2, x/2) = p, P the regularised lower incomplete gamma function (series and
// continued fraction, Numerical Recipes 3rd ed. section 6.2), solved by Newton's method started
// from the Wilson-Hilferty approximation (chi2_p ~ k (1 - 2/(9k) + z_p sqrt(2/(9k)))^3,
// Wilson & Hilferty 1931) and safeguarded by bisection; relative accuracy ~1e-10.
double ChiSquareQuantile(double p, double k);

// The two-sided 95 % band of the mean of `samples` independent NEES values of a consistent
// estimator with state dimension `dim`: N * mean ~ chi2(N dim), so the band is
// [chi2_0.025(N dim), chi2_0.975(N dim)] / N (Bar-Shalom, Li & Kirubarajan, "Estimation with
// Applications to Tracking and Navigation", 2001, section 5.4.2).
std::array<double, 2> MeanNeesBand95(long samples, int dim);

// e^T P^-1 e for the 6x6 row-major covariance P (Cholesky; NaN when P is not positive definite
// or not finite, e.g. an estimator that does not know its covariance).
double Nees6(const double error[6], const double covariance[36]);

class EstimationMetrics {
 public:
  static constexpr int kDim = 6;  // (p, v)
  explicit EstimationMetrics(int n_vehicles);
  // One sample of every vehicle: the estimates and the truth of the same step.
  void Add(const std::vector<mjfEstimate>& estimates, const std::vector<mjfVehicleState>& truth);
  // The summary block. counts[i]: vehicle i's {fused, gated, too_old} (NaN: not reported), or
  // empty when the estimator reports none.
  nlohmann::ordered_json Summary(const std::vector<std::array<double, 3>>& counts) const;
  // The sums per vehicle, both ways (checkpoints).
  template <typename Archive>
  void VisitState(Archive& a) {
    for (Sums& s : sums_) {
      a(s.position_sq, s.velocity_sq, s.nees, s.relative_sq, s.samples, s.nees_samples);
      a(s.nees_in_band);
    }
  }

 private:
  struct Sums {
    double position_sq = 0, velocity_sq = 0, nees = 0;
    double relative_sq = 0;  // |e_i - e_0|^2: the error of the position relative to the leader
    long samples = 0, nees_samples = 0, nees_in_band = 0;
    Sums& operator+=(const Sums& o);
  };
  // One vehicle's (or the pooled followers') accuracy as summary.json writes it; the
  // relative-to-leader RMS only where it means something (not for the leader itself).
  static nlohmann::ordered_json SumsJson(const Sums& s, bool relative_to_leader);
  std::vector<Sums> sums_;
  std::array<double, 2> single_band_;  // chi2(6) 95 % band of one NEES sample
};

}  // namespace mjf::runner

#endif  // MJFORMATION_RECORD_ESTIMATION_METRICS_HPP_
