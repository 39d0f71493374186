// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include "mjformation/app/sweep_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mjf::runner {

double StudentT975(int df) {
  // t_{0.975, df}, df = 1..30 (any statistics table, e.g. NIST/SEMATECH e-Handbook 1.3.6.7.2).
  static const double kTable[30] = {12.7062, 4.3027, 3.1824, 2.7764, 2.5706, 2.4469, 2.3646, 2.3060,
                                    2.2622,  2.2281, 2.2010, 2.1788, 2.1604, 2.1448, 2.1314, 2.1199,
                                    2.1098,  2.1009, 2.0930, 2.0860, 2.0796, 2.0739, 2.0687, 2.0639,
                                    2.0595,  2.0555, 2.0518, 2.0484, 2.0452, 2.0423};
  if (df < 1) return std::numeric_limits<double>::quiet_NaN();
  if (df <= 30) return kTable[df - 1];
  // Cornish-Fisher expansion (Abramowitz & Stegun 26.7.5) about z = 1.959964.
  const double z = 1.959963984540054, n = df;
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  return z + (z3 + z) / (4 * n) + (5 * z5 + 16 * z3 + 3 * z) / (96 * n * n) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * n * n * n);
}

SampleStats Describe(const std::vector<double>& samples) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  SampleStats s;
  s.n = static_cast<int>(samples.size());
  s.mean = s.std = s.ci95_low = s.ci95_high = kNaN;
  if (s.n == 0) return s;
  double sum = 0;
  bool all_equal = true;
  for (double v : samples) {
    sum += v;
    all_equal = all_equal && v == samples[0];
  }
  // Identical samples (a deterministic cell): exactly that value, no rounding residue.
  s.mean = all_equal ? samples[0] : sum / s.n;
  if (s.n < 2) return s;
  double squares = 0;
  for (double v : samples) squares += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(squares / (s.n - 1));
  const double half = StudentT975(s.n - 1) * s.std / std::sqrt(static_cast<double>(s.n));
  s.ci95_low = s.mean - half;
  s.ci95_high = s.mean + half;
  const bool non_negative =
      std::all_of(samples.begin(), samples.end(), [](double v) { return v >= 0; });
  if (non_negative && s.ci95_low < 0) {
    s.ci95_low = 0;
    s.cut_at_zero = true;
  }
  return s;
}

}  // namespace mjf::runner
