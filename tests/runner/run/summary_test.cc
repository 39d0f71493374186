// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/run/src/summary.cc: the fields of summary.json, their order, and how complete, error,
// signal and timing are written.
#include "mjformation/run/summary.hpp"

#include <gtest/gtest.h>

#include <csignal>

#include "mjformation/record/output.hpp"
#include "mjformation/sim/simulation.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using Json = nlohmann::ordered_json;
using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;

std::vector<std::string> Keys(const Json& j) {
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  return keys;
}

class SummaryTest : public ::testing::Test {
 protected:
  SummaryTest() : sim_(Parse(PointMassExperiment(-2, 1, 2, 1, 0.5))) {}
  Simulation sim_;
};

// The closing line's note: nothing while Assumption 1 holds (or has no bounds); when it does not,
// when, how often and by how much, from summary.json's own numbers (Exp 2's, stock).
TEST(Assumption1TextTest, SaysWhenTheLeaderLeftTheBounds) {
  Json s = {{"leader_acceleration",
             {{"bounds", {-1.0, 1.0}},
              {"bounds_source", "formation"},
              {"fraction_outside", 0.023575},
              {"first_violation_time_s", 0.073},
              {"max_excess", 4.9274751488336275},
              {"assumption1_holds", false}}}};
  EXPECT_EQ(Assumption1Text(s),
            "Assumption 1 does not hold: the leader's measured acceleration left the bounds [-1, "
            "1] m/s^2 (formation) on 2.36 % of the steps, first at t = 0.073 s, by up to 4.93 "
            "m/s^2; Theorem 2's band is not guaranteed (summary.json leader_acceleration)");
  s["leader_acceleration"]["assumption1_holds"] = true;
  EXPECT_EQ(Assumption1Text(s), "");
  s["leader_acceleration"]["assumption1_holds"] = nullptr;  // no bounds to judge
  EXPECT_EQ(Assumption1Text(s), "");
  EXPECT_EQ(Assumption1Text(Json::object()), "");
}

TEST_F(SummaryTest, AnInterruptedRunSaysWhyAndWhere) {
  RunResult r;
  r.complete = false;
  r.error = "interrupted by SIGTERM";
  r.signal = SIGTERM;
  r.sim_time_s = 0.25;
  r.steps = 250;
  r.wall_time_s = 0.5;
  const Json recorded = {{"metrics", {{"sigma_f_mean", 1.5}}},
                         {"leader_acceleration", {{"samples", 250}}},
                         {"snapshots", {"snapshots/t000.10.png"}}};
  const Json s = BuildSummary(sim_, r, recorded);
  EXPECT_EQ(Keys(s), (std::vector<std::string>{"experiment",
                                               "complete",
                                               "error",
                                               "interrupted_by_signal",
                                               "paper_experiment",
                                               "sim_time_s",
                                               "duration_s",
                                               "timestep_s",
                                               "steps",
                                               "seed",
                                               "config_sha256",
                                               "versions",
                                               "n_followers",
                                               "vehicle_model",
                                               "rotor_model",
                                               "plugins",
                                               "shape",
                                               "metrics",
                                               "plugin_report",
                                               "snapshots",
                                               "leader_acceleration",
                                               "timing"}));
  EXPECT_EQ(s["experiment"], "unit");
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["error"], "interrupted by SIGTERM");
  EXPECT_EQ(s["interrupted_by_signal"], SIGTERM);
  EXPECT_EQ(s["sim_time_s"], 0.25);
  EXPECT_EQ(s["duration_s"], 0.5);
  EXPECT_EQ(s["timestep_s"], 0.001);
  EXPECT_EQ(s["steps"], 250);
  EXPECT_EQ(s["metrics"], recorded["metrics"]);
  EXPECT_EQ(s["snapshots"], recorded["snapshots"]);
  EXPECT_EQ(s["leader_acceleration"], recorded["leader_acceleration"]);
  EXPECT_DOUBLE_EQ(s["timing"]["real_time_factor"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(s["timing"]["steps_per_second"].get<double>(), 500.0);
  EXPECT_EQ(s["timing"]["wall_time_s"], 0.5);
}

TEST_F(SummaryTest, ACompleteRunHasNoErrorAndNoSignal) {
  RunResult r;
  r.complete = true;
  r.error = "ignored when complete";
  const Json s = BuildSummary(sim_, r, Json::object());
  EXPECT_TRUE(s["error"].is_null());
  EXPECT_FALSE(s.contains("interrupted_by_signal"));
  EXPECT_TRUE(s["metrics"].is_null());  // nothing recorded
  EXPECT_EQ(s["snapshots"], Json::array());
  EXPECT_FALSE(s.contains("network"));  // central execution
  EXPECT_FALSE(s.contains("sensors"));  // ideal and calm: nothing about them
  EXPECT_FALSE(s.contains("wind"));
  // No wall time (e.g. a run stopped before its loop): rates 0, not inf or NaN.
  EXPECT_EQ(s["timing"]["real_time_factor"], 0.0);
  EXPECT_EQ(s["timing"]["steps_per_second"], 0.0);
}

TEST_F(SummaryTest, WhatRan) {
  const Json s = BuildSummary(sim_, RunResult{}, Json::object());
  EXPECT_EQ(s["seed"], 1);
  EXPECT_EQ(s["config_sha256"], Sha256Hex(ConfigEcho(sim_.config())));
  EXPECT_EQ(s["config_sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(s["versions"]["plugin_abi"], MJF_ABI_VERSION);
  EXPECT_EQ(s["versions"]["mujoco"], mj_versionString());
  EXPECT_EQ(s["n_followers"], 2);
  EXPECT_EQ(s["vehicle_model"], "pointmass");
  EXPECT_EQ(s["rotor_model"], "actuator");
  EXPECT_EQ(s["plugins"]["leader"]["name"], "hover");
  EXPECT_EQ(s["plugins"]["formation"]["name"], "hover");
  EXPECT_EQ(s["plugins"]["attitude"]["name"], "pointmass_direct");
  // Attributes with the values in use, defaults included.
  for (const auto& [k, v] : sim_.attitude_plugin(0).attributes()) {
    EXPECT_EQ(s["plugins"]["attitude"]["attributes"][k], v) << k;
  }
  EXPECT_EQ(s["shape"]["type"], "offsets");
  EXPECT_EQ(s["plugin_report"], Json::object());  // hover reports nothing
}

TEST_F(SummaryTest, RealismSectionsAppearOnlyWhenSwitchedOn) {
  Simulation windy(
      Parse(PointMassExperiment(-2, 1, 2, 1, 0.5, "", "[wind]\nmean = [3.0, 0.0, 0.0]\n")));
  const Json s = BuildSummary(windy, RunResult{}, Json::object());
  ASSERT_TRUE(s.contains("wind"));
  EXPECT_EQ(s["wind"]["mean"], Json::parse("[3.0, 0.0, 0.0]"));
  EXPECT_FALSE(s.contains("sensors"));
}

}  // namespace
}  // namespace mjf::runner
