// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The predicted delay margin: rho(L_H^-1 A) against a dense computation, and the
// margins' formulas on Exp 2's ring.
#include "mjformation/control/delay_margin.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "mjformation/formation/graph.hpp"

namespace mjf::runner {
namespace {

// Exp 2: a bidirectional ring of six, only follower 1 hears the leader.
formation::Graph Ring() {
  std::vector<formation::Edge> edges;
  for (int i = 0; i < 6; ++i) {
    edges.push_back({i, (i + 1) % 6, 1.0});
    edges.push_back({(i + 1) % 6, i, 1.0});
  }
  return formation::Graph(6, {1, 0, 0, 0, 0, 0}, edges);
}

TEST(DelayMarginTest, CouplingRadiusMatchesDenseEigenvalues) {
  const formation::Graph g = Ring();
  const Eigen::MatrixXd lh = Eigen::MatrixXd(g.laplacian_h());
  Eigen::MatrixXd a = -lh;
  a.diagonal().setZero();
  const Eigen::MatrixXd m = lh.inverse() * a;
  const double dense = m.eigenvalues().cwiseAbs().maxCoeff();
  EXPECT_NEAR(CouplingSpectralRadius(g), dense, 1e-9 * dense);
  EXPECT_GT(dense, 17.0);  // the 18: a slow ring
  EXPECT_LT(dense, 19.0);
}

TEST(DelayMarginTest, MarginsFollowTheLinearisation) {
  const double rho = CouplingSpectralRadius(Ring());
  const DelayMargin m = PredictedDelayMargin(0.05, 4.5, rho);  // Exp 2
  EXPECT_NEAR(m.without_prediction, 0.05 / (0.775 * rho), 1e-15);
  EXPECT_GT(m.without_prediction, 0.003);
  EXPECT_LT(m.without_prediction, 0.004);
  EXPECT_EQ(m.with_prediction, 0.05);  // (1 - qT) rho > 1: the hold interval is the edge
  EXPECT_FALSE(m.with_prediction_capped);
  const DelayMargin weak = PredictedDelayMargin(0.05, 4.5, 0.5);  // (1 - qT) rho < 1
  EXPECT_TRUE(weak.with_prediction_capped);
  EXPECT_EQ(weak.with_prediction, 0.1);
}

// summary.json's network.delay_margin: the margins of PredictedDelayMargin for the law's T and
// q beside rho; a loop that never closes (1 - qT <= 0) has no finite margin, written null.
TEST(DelayMarginTest, SummaryWritesTheMarginsAndNullForNoLoop) {
  const double rho = CouplingSpectralRadius(Ring());
  const nlohmann::json s = DelayMarginSummary(0.05, 4.5, rho);
  EXPECT_EQ(s["coupling_spectral_radius"].get<double>(), rho);
  EXPECT_EQ(s["period_s"].get<double>(), 0.05);
  EXPECT_EQ(s["q"].get<double>(), 4.5);
  EXPECT_EQ(s["without_prediction_s"].get<double>(),
            PredictedDelayMargin(0.05, 4.5, rho).without_prediction);
  EXPECT_EQ(s["with_prediction_s"].get<double>(), 0.05);
  EXPECT_FALSE(s["with_prediction_is_lower_bound"].get<bool>());
  const nlohmann::json none = DelayMarginSummary(0.05, 20.0, rho);  // qT = 1
  EXPECT_TRUE(none["without_prediction_s"].is_null());
  EXPECT_TRUE(none["with_prediction_s"].is_null());
}

}  // namespace
}  // namespace mjf::runner
