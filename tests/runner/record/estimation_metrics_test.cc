// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/record/src/estimation_metrics.cc: chi-square quantiles against published tables, the
// NEES of a known error and covariance, and the summary block of two vehicles.
#include "mjformation/record/estimation_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace mjf::runner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Abramowitz & Stegun table 26.8 / NIST e-Handbook 1.3.6.7.4 (upper-tail critical values).
TEST(ChiSquareTest, QuantilesMatchTheTables) {
  struct Row {
    double k, lower, upper;  // 0.025 and 0.975 quantiles
  };
  for (const Row& r : {Row{1, 0.000982069, 5.023886}, Row{6, 1.237347, 14.449375},
                       Row{10, 3.246973, 20.483177}, Row{100, 74.221927, 129.561197}}) {
    EXPECT_NEAR(ChiSquareQuantile(0.025, r.k), r.lower, 2e-6 * r.k) << "k = " << r.k;
    EXPECT_NEAR(ChiSquareQuantile(0.975, r.k), r.upper, 2e-6 * r.k) << "k = " << r.k;
  }
  EXPECT_TRUE(std::isnan(ChiSquareQuantile(0.0, 6)));
  EXPECT_TRUE(std::isnan(ChiSquareQuantile(0.5, 0)));
}

// For many degrees of freedom (a run's NEES samples times 6) Wilson-Hilferty is accurate to a
// few 1e-6 relative; the exact routine must agree with it there.
TEST(ChiSquareTest, LargeDegreesOfFreedomAgreeWithWilsonHilferty) {
  for (double k : {1000.0, 9006.0, 60006.0}) {
    const double v = 2.0 / (9.0 * k);
    const double wh = k * std::pow(1.0 - v + 1.959963985 * std::sqrt(v), 3);
    EXPECT_NEAR(ChiSquareQuantile(0.975, k) / wh, 1.0, 1e-5) << "k = " << k;
  }
}

TEST(ChiSquareTest, MeanNeesBandNarrowsAroundTheDimension) {
  const auto one = MeanNeesBand95(1, 6);
  EXPECT_NEAR(one[0], 1.237347, 1e-5);
  EXPECT_NEAR(one[1], 14.449375, 1e-5);
  const auto many = MeanNeesBand95(1000, 6);
  EXPECT_LT(many[0], 6.0);
  EXPECT_GT(many[1], 6.0);
  // ~ 6 -/+ 1.96 sqrt(2 * 6 / 1000)
  EXPECT_NEAR(many[1] - many[0], 2 * 1.96 * std::sqrt(12.0 / 1000), 0.01);
  EXPECT_TRUE(std::isnan(MeanNeesBand95(0, 6)[0]));
}

TEST(NeesTest, KnownErrorAndCovariance) {
  double p[36] = {};
  for (int k = 0; k < 6; ++k) p[7 * k] = 4.0;
  p[1] = p[6] = 1.0;  // correlated x position and y position
  const double e[6] = {2, 0, 0, 0, 0, 2};
  // [[4, 1], [1, 4]]^-1 = [[4, -1], [-1, 4]] / 15: e_x^2 4/15, plus e_vz^2 / 4
  EXPECT_NEAR(Nees6(e, p), 4.0 * 4.0 / 15.0 + 1.0, 1e-12);
  double unknown[36];
  for (double& c : unknown) c = kNaN;
  EXPECT_TRUE(std::isnan(Nees6(e, unknown)));
  double singular[36] = {};
  EXPECT_TRUE(std::isnan(Nees6(e, singular)));
}

// An error common to every vehicle cancels in the position relative to the leader.
TEST(EstimationMetricsTest, ACommonErrorCancelsRelativeToTheLeader) {
  EstimationMetrics m(3);
  std::vector<mjfVehicleState> truth(3);
  std::vector<mjfEstimate> est(3);
  for (auto& e : est) e.state.pos[1] = 2.5;
  est[2].state.pos[0] = 0.3;
  m.Add(est, truth);
  const auto s = m.Summary({});
  EXPECT_NEAR(s["vehicles"][1]["position_rms_m"].get<double>(), 2.5, 1e-12);
  EXPECT_NEAR(s["vehicles"][1]["position_rms_relative_to_leader_m"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(s["vehicles"][2]["position_rms_relative_to_leader_m"].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(s["followers"]["position_rms_relative_to_leader_m"].get<double>(),
              std::sqrt(0.09 / 2), 1e-12);
}

TEST(EstimationMetricsTest, SummaryOfTwoVehicles) {
  EstimationMetrics m(2);
  std::vector<mjfVehicleState> truth(2);
  std::vector<mjfEstimate> est(2);
  for (auto& e : est) {
    for (int k = 0; k < 36; ++k) e.covariance[k] = k % 7 == 0 ? 1.0 : 0.0;
  }
  // Vehicle 1: position errors 3 then 4 along x (RMS 3.54), velocity error 1 along z.
  est[1].state.pos[0] = 3.0;
  est[1].state.vel[2] = 1.0;
  m.Add(est, truth);
  est[1].state.pos[0] = 4.0;
  m.Add(est, truth);
  const auto s = m.Summary({{10, 2, 1}, {20, 0, kNaN}});
  EXPECT_EQ(s["state_dim"], 6);
  const auto& v1 = s["vehicles"][1];
  EXPECT_EQ(v1["samples"], 2);
  EXPECT_NEAR(v1["position_rms_m"].get<double>(), std::sqrt(12.5), 1e-12);
  EXPECT_NEAR(v1["velocity_rms_m_s"].get<double>(), 1.0, 1e-12);
  // The leader's estimate is exact here: relative and absolute errors agree.
  EXPECT_NEAR(v1["position_rms_relative_to_leader_m"].get<double>(), std::sqrt(12.5), 1e-12);
  EXPECT_FALSE(s["vehicles"][0].contains("position_rms_relative_to_leader_m"));
  EXPECT_NEAR(v1["nees_mean"].get<double>(), (10.0 + 17.0) / 2, 1e-12);
  EXPECT_EQ(v1["fused"], 20);
  EXPECT_TRUE(v1["too_old"].is_null());
  EXPECT_EQ(s["vehicles"][0]["nees_mean"], 0.0);
  EXPECT_EQ(s["vehicles"][0]["gated"], 2);
  // The followers' block pools vehicles 1..N: here vehicle 1 alone.
  EXPECT_EQ(s["followers"]["position_rms_m"], v1["position_rms_m"]);
  EXPECT_EQ(s["followers"]["nees_band_95"], v1["nees_band_95"]);
  // NEES 10 and 17 both lie inside the single-sample band [1.24, 14.45]? 10 does, 17 not.
  EXPECT_EQ(v1["nees_fraction_in_single_band"], 0.5);
}

}  // namespace
}  // namespace mjf::runner
