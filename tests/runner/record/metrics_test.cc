// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/record/src/metrics.cc: sigma_f (eq. 68), slots, final slot errors and the minimum
// separation of a known configuration, computed by hand; the minimum separation sweep against brute
// force.
#include "mjformation/record/metrics.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>
#include <random>

#include "mjformation/sim/simulation.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;

double BruteForceSeparation(const std::vector<double>& xyz) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < xyz.size() / 3; ++a) {
    for (size_t b = a + 1; b < xyz.size() / 3; ++b) {
      best = std::min(best, std::sqrt(std::pow(xyz[3 * a] - xyz[3 * b], 2) +
                                      std::pow(xyz[3 * a + 1] - xyz[3 * b + 1], 2) +
                                      std::pow(xyz[3 * a + 2] - xyz[3 * b + 2], 2)));
    }
  }
  return best;
}

TEST(MetricsTest, MinimumSeparationOfKnownPoints) {
  std::vector<std::pair<double, int>> order;
  // (0,0,0), (3,4,0), (10,0,0), (3,4,12): the closest pair is 5 m apart.
  EXPECT_DOUBLE_EQ(MinimumSeparation({0, 0, 0, 3, 4, 0, 10, 0, 0, 3, 4, 12}, &order), 5.0);
  // Same x for everyone: the sweep cannot prune on x and must still find the pair in z.
  EXPECT_DOUBLE_EQ(MinimumSeparation({1, 0, 0, 1, 0, 7, 1, 0, 2.5}, &order), 2.5);
  EXPECT_EQ(MinimumSeparation({1, 2, 3}, &order), std::numeric_limits<double>::infinity());
  EXPECT_EQ(MinimumSeparation({}, &order), std::numeric_limits<double>::infinity());
}

TEST(MetricsTest, MinimumSeparationMatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-20, 20);
  std::vector<std::pair<double, int>> order;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> xyz(3 * (2 + trial % 40));
    for (double& v : xyz) v = u(rng);
    EXPECT_EQ(MinimumSeparation(xyz, &order), BruteForceSeparation(xyz)) << trial;
  }
}

// Followers displaced from their slots (-2, 0) and (2, 0) by (0.3, 0.4) and (0, -1.2), at rest:
// sigma_f = sqrt(0.3^2 + 0.4^2 + 1.2^2) = 1.3 (eq. 68; velocities all zero at t = 0).
TEST(MetricsTest, SigmaSlotsAndErrorsOfAKnownConfiguration) {
  Simulation sim(Parse(PointMassExperiment(-1.7, 0.4, 2.0, -1.2, 0.01, "reaching_band = 0.2\n")));
  OnlineMetrics metrics(sim);
  sim.ComputeControls();
  std::vector<double> slots(6, -99);
  const double sigma_f = metrics.Sample(sim, &slots, true);
  EXPECT_NEAR(sigma_f, 1.3, 1e-12);
  // Slots: the leader's own setpoint, then leader + offset.
  EXPECT_NEAR(slots[0], 0.0, 1e-12);
  EXPECT_NEAR(slots[1], 0.0, 1e-12);
  EXPECT_NEAR(slots[2], -2.0, 1e-12);
  EXPECT_NEAR(slots[3], 0.0, 1e-12);
  EXPECT_NEAR(slots[4], 2.0, 1e-12);
  EXPECT_NEAR(slots[5], 0.0, 1e-12);
  metrics.StepControls(sim);
  const auto m = metrics.Summary(sim);
  EXPECT_NEAR(m["sigma_f_mean"].get<double>(), 1.3, 1e-12);
  EXPECT_EQ(m["sigma_f_samples"], 1);
  EXPECT_NEAR(m["sigma_f_initial"].get<double>(), 1.3, 1e-12);
  EXPECT_NEAR(m["sigma_f_final"].get<double>(), 1.3, 1e-12);
  ASSERT_EQ(m["final_slot_error_m"].size(), 2u);
  EXPECT_NEAR(m["final_slot_error_m"][0].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(m["final_slot_error_m"][1].get<double>(), 1.2, 1e-12);
  EXPECT_NEAR(m["max_final_slot_error_m"].get<double>(), 1.2, 1e-12);
  // Leader (0, 0) to follower 1 (-1.7, 0.4), all at the same altitude: sqrt(3.05).
  EXPECT_NEAR(m["min_separation_m"].get<double>(), std::sqrt(3.05), 1e-12);
  EXPECT_EQ(m["reaching_band"].get<double>(), 0.2);  // [run] reaching_band
  // Hover reports no sliding variables: no reaching time.
  EXPECT_TRUE(m["reaching_time_s"].is_null());
  EXPECT_TRUE(m["max_abs_s"].is_null());
  EXPECT_EQ(m["saturation_time_s"].get<double>(), 0.0);
  EXPECT_EQ(m["max_follower_tilt_deg_in_window"].get<double>(), 0.0);  // a point mass
  EXPECT_EQ(m["sigma_f_window"], nlohmann::ordered_json::parse("[0.0, 0.01]"));
}

TEST(MetricsTest, OnlyAccumulatedSamplesEnterTheStatistics) {
  Simulation sim(Parse(PointMassExperiment(-1.7, 0.4, 2.0, -1.2)));
  OnlineMetrics metrics(sim);
  sim.ComputeControls();
  std::vector<double> slots(6);
  // A render-only sample: sigma_f is computed but does not count.
  EXPECT_NEAR(metrics.Sample(sim, &slots, false), 1.3, 1e-12);
  const auto m = metrics.Summary(sim);
  EXPECT_EQ(m["sigma_f_samples"], 0);
  EXPECT_TRUE(m["sigma_f_mean"].is_null());
  EXPECT_TRUE(m["sigma_f_initial"].is_null());
  EXPECT_TRUE(m["min_separation_m"].is_null());  // no record tick: +inf, written as null
  // Without a band in [run] (and no "delta" from hover): the default 0.1.
  EXPECT_EQ(m["reaching_band"].get<double>(), 0.1);
}

TEST(MetricsTest, MeanOverTheWindowOnly) {
  // Two record ticks at t = 0 and t = 0.01, window [0.005, 0.01]: only the second counts.
  ExperimentConfig c = Parse(PointMassExperiment(-1.7, 0.4, 2.0, -1.2, 0.01));
  c.metric_window = {0.005, 0.01};
  Simulation windowed(c);
  // Follower 1 starts at 1 m/s in x: eq. (68) adds its velocity error, sqrt(1.69 + 1).
  const mjModel* model = windowed.model();
  windowed.data()->qvel[model->jnt_dofadr[mj_name2id(model, mjOBJ_JOINT, "uav1_x")]] = 1.0;
  OnlineMetrics metrics(windowed);
  std::vector<double> slots(6);
  std::vector<double> sigma;
  for (int64_t step = 0; step <= windowed.total_steps(); ++step) {
    windowed.ComputeControls();
    if (step % 10 == 0) sigma.push_back(metrics.Sample(windowed, &slots, true));
    if (step < windowed.total_steps()) windowed.Integrate();
  }
  ASSERT_EQ(sigma.size(), 2u);
  EXPECT_NEAR(sigma[0], std::sqrt(2.69), 1e-12);
  const auto m = metrics.Summary(windowed);
  EXPECT_EQ(m["sigma_f_samples"], 1);
  EXPECT_DOUBLE_EQ(m["sigma_f_mean"].get<double>(), sigma[1]);
  EXPECT_DOUBLE_EQ(m["sigma_f_initial"].get<double>(), sigma[0]);
  EXPECT_DOUBLE_EQ(m["sigma_f_final"].get<double>(), sigma[1]);
  EXPECT_NE(sigma[0], sigma[1]);                        // the followers moved towards their slots
  EXPECT_FALSE(m.contains("sigma_f_sampled_until_s"));  // it sampled to the window's end
}

// A run stopped at 0.01 s of a window [0.005, 0.02]: the mean covers less than the window it
// names, and the summary says up to when it sampled.
TEST(MetricsTest, AWindowCutShortSaysWhenItsSamplesEnd) {
  ExperimentConfig c = Parse(PointMassExperiment(-1.7, 0.4, 2.0, -1.2, 0.02));
  c.metric_window = {0.005, 0.02};
  Simulation stopped(c);
  OnlineMetrics metrics(stopped);
  std::vector<double> slots(6);
  for (int64_t step = 0; step <= 10; ++step) {  // half the run: records at 0 and 0.01 s
    stopped.ComputeControls();
    if (step % 10 == 0) metrics.Sample(stopped, &slots, true);
    if (step < 10) stopped.Integrate();
  }
  const auto m = metrics.Summary(stopped);
  EXPECT_EQ(m["sigma_f_samples"], 1);
  EXPECT_EQ(m["sigma_f_window"], (nlohmann::ordered_json{0.005, 0.02}));
  EXPECT_DOUBLE_EQ(m["sigma_f_sampled_until_s"].get<double>(), 0.01);
}

TEST(MetricsTest, WithoutAFormationTheSlotsAreTheHeldSetpoints) {
  Simulation sim(Parse(PointMassExperiment(-1.7, 0.4, 2.0, -1.2, 0.02, "", "", "none")));
  ASSERT_EQ(sim.shape(), nullptr);
  OnlineMetrics metrics(sim);
  sim.ComputeControls();
  std::vector<double> slots(6);
  EXPECT_TRUE(std::isnan(metrics.Sample(sim, &slots, true)));
  // hover holds each follower where it started: its slot is its own position.
  EXPECT_NEAR(slots[2], -1.7, 1e-12);
  EXPECT_NEAR(slots[3], 0.4, 1e-12);
  EXPECT_NEAR(slots[4], 2.0, 1e-12);
  EXPECT_NEAR(slots[5], -1.2, 1e-12);
  const auto m = metrics.Summary(sim);
  EXPECT_NEAR(m["max_final_slot_error_m"].get<double>(), 0.0, 1e-12);
  EXPECT_TRUE(m["sigma_f_mean"].is_null());
  EXPECT_EQ(m["sigma_f_samples"], 0);
  EXPECT_NEAR(m["min_separation_m"].get<double>(), std::sqrt(3.05), 1e-12);
}

}  // namespace
}  // namespace mjf::runner
