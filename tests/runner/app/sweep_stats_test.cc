// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/app/src/sweep_stats.cc: Student's t quantile and the per-cell mean, standard deviation and
// 95 % interval, against values computed by hand (no statistics library).
#include "mjformation/app/sweep_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mjf::runner {
namespace {

TEST(SweepStatsTest, QuantileBelowOneDegreeOfFreedomIsNaN) {
  EXPECT_TRUE(std::isnan(StudentT975(0)));
  EXPECT_TRUE(std::isnan(StudentT975(-3)));
}

TEST(SweepStatsTest, QuantileJoinsTheTableAndTheExpansionSmoothly) {
  // t_{0.975} beyond the table's end (df > 30), to 6 decimals: the expansion (error < 1e-5
  // here) must give them; leaving out its 1/df^3 term is off by 9e-5 at df = 31.
  EXPECT_NEAR(StudentT975(30), 2.0423, 1e-4);
  EXPECT_NEAR(StudentT975(31), 2.039513, 1e-5);
  EXPECT_NEAR(StudentT975(35), 2.030108, 1e-5);
  EXPECT_NEAR(StudentT975(50), 2.008559, 1e-5);
  EXPECT_NEAR(StudentT975(1000), 1.962339, 1e-5);
  // A quantile of t falls with the degrees of freedom, across the table/expansion seam too.
  for (int df = 1; df < 200; ++df) EXPECT_GT(StudentT975(df), StudentT975(df + 1)) << df;
  EXPECT_GT(StudentT975(1 << 20), 1.959963);
}

TEST(SweepStatsTest, EightSamplesByHand) {
  // {2, 4, 4, 4, 5, 5, 7, 9}: mean 5, squared deviations sum to 32, s = sqrt(32 / 7),
  // half width = t_{0.975, 7} s / sqrt(8) with t = 2.3646.
  const SampleStats s = Describe({2, 4, 4, 4, 5, 5, 7, 9});
  EXPECT_EQ(s.n, 8);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_NEAR(s.std, std::sqrt(32.0 / 7.0), 1e-14);
  const double half = 2.3646 * std::sqrt(32.0 / 7.0) / std::sqrt(8.0);
  EXPECT_NEAR(s.ci95_low, 5.0 - half, 1e-12);
  EXPECT_NEAR(s.ci95_high, 5.0 + half, 1e-12);
}

TEST(SweepStatsTest, TwoSamplesUseTheOneDegreeOfFreedomFactor) {
  // {-1, 1}: s = sqrt(2), half width = 12.7062 sqrt(2) / sqrt(2); a sample below 0: not cut.
  const SampleStats s = Describe({-1, 1});
  EXPECT_DOUBLE_EQ(s.mean, 0.0);
  EXPECT_NEAR(s.std, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(s.ci95_high - s.mean, 12.7062, 1e-12);
  EXPECT_NEAR(s.mean - s.ci95_low, 12.7062, 1e-12);
  EXPECT_FALSE(s.cut_at_zero);
}

TEST(SweepStatsTest, AnIntervalOfNonNegativeSamplesStopsAtZero) {
  // {0.5, 1, 10}: mean 3.8333, s = 5.3463, t_{0.975, 2} = 4.3027: [-9.448, 17.11] as a plain t
  // interval; every sample >= 0, so the mean cannot be negative and the low end is 0.
  const SampleStats s = Describe({0.5, 1, 10});
  EXPECT_NEAR(s.mean, 11.5 / 3, 1e-14);
  const double half = 4.3027 * s.std / std::sqrt(3.0);
  EXPECT_NEAR(s.ci95_high, s.mean + half, 1e-12);
  EXPECT_EQ(s.ci95_low, 0.0);
  EXPECT_TRUE(s.cut_at_zero);
  // An interval already above 0 is the plain t interval.
  const SampleStats above = Describe({2, 4, 4, 4, 5, 5, 7, 9});
  EXPECT_GT(above.ci95_low, 0.0);
  EXPECT_FALSE(above.cut_at_zero);
}

TEST(SweepStatsTest, IdenticalSamplesGiveExactlyThatValue) {
  // 0.1 + 0.1 + 0.1 = 0.30000000000000004 and / 3 is not 0.1: a deterministic cell must still
  // report its value exactly, with a zero-width interval.
  const SampleStats s = Describe({0.1, 0.1, 0.1});
  EXPECT_EQ(s.mean, 0.1);
  EXPECT_EQ(s.std, 0.0);
  EXPECT_EQ(s.ci95_low, 0.1);
  EXPECT_EQ(s.ci95_high, 0.1);
}

TEST(SweepStatsTest, TooFewSamples) {
  const SampleStats none = Describe({});
  EXPECT_EQ(none.n, 0);
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_TRUE(std::isnan(none.std));
  const SampleStats one = Describe({-4.5});
  EXPECT_EQ(one.n, 1);
  EXPECT_EQ(one.mean, -4.5);
  EXPECT_TRUE(std::isnan(one.std));
  EXPECT_TRUE(std::isnan(one.ci95_low));
  EXPECT_TRUE(std::isnan(one.ci95_high));
}

}  // namespace
}  // namespace mjf::runner
