// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// Statistics of a metric over the seeds of one sweep cell (Monte Carlo).
#ifndef MJFORMATION_APP_SWEEP_STATS_HPP_
#define MJFORMATION_APP_SWEEP_STATS_HPP_

#include <vector>

namespace mjf::runner {

// The 97.5 % quantile of Student's t distribution with `df` >= 1 degrees of freedom: the factor
// of a two-sided 95 % confidence interval of a mean. Exact table to df = 30 (to 4 decimals),
// then the Cornish-Fisher expansion about the normal quantile (error < 1e-4).
double StudentT975(int df);

struct SampleStats {
  int n = 0;            // samples
  double mean = 0;      // NaN when n = 0
  double std = 0;       // sample standard deviation (n - 1); NaN when n < 2
  double ci95_low = 0;  // mean -+ t_{0.975, n-1} std / sqrt(n); NaN when n < 2
  double ci95_high = 0;
};
SampleStats Describe(const std::vector<double>& samples);

}  // namespace mjf::runner

#endif  // MJFORMATION_APP_SWEEP_STATS_HPP_
