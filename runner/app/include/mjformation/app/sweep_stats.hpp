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
  double ci95_low = 0;  // mean -+ t_{0.975, n-1} std / sqrt(n), cut at 0 (below); NaN when n < 2
  double ci95_high = 0;
  bool cut_at_zero = false;  // the t interval reached below 0 and was cut there
};

// The method of SampleStats' interval, as sweep.json and the summary state it.
inline constexpr const char* kCi95Method =
    "Student t interval of the mean (mean -+ t_{0.975, n-1} s / sqrt(n)), cut at 0 when every "
    "run's value is >= 0; assumes a roughly normal mean, so with few runs of a skewed metric "
    "it is a rough guide";

// Mean, standard deviation and the 95 % interval of the mean. When every sample is >= 0 (each
// metric summary.json lists is a distance, time, norm or count, never negative) the interval is
// cut to [0, inf): the mean cannot lie below 0, and leaving out values the mean cannot take
// keeps the interval's coverage. A sample below 0 leaves the interval as it is.
SampleStats Describe(const std::vector<double>& samples);

}  // namespace mjf::runner

#endif  // MJFORMATION_APP_SWEEP_STATS_HPP_
