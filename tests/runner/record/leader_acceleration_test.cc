// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The leader's measured acceleration: summary.json "leader_acceleration" from
// MuJoCo's velocity sensor, Assumption 1 checked against the formation plugin's bounds, the
// timeseries columns only when [run] record_leader_acceleration = true, and the maneuvering
// leaders' bad input refused before the run with FILE:LINE: [leader].
#include <dirent.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "mjformation/sim/simulation.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::HasSubstr;

// Point mass swarm (its force is m a, so the measured acceleration is the command) with a
// bang_bang leader at +-leader_bound and smc_discrete told [-1, 1].
std::string Experiment(double leader_bound, bool record) {
  std::string t = "[run]\nname = \"leader_acc\"\nduration = 3.0\n";
  if (record) t += "record_leader_acceleration = true\n";
  t += "[vehicles]\nmodel = \"pointmass\"\nfollowers = 2\naltitude = 2.0\n"
       "leader_start = [0.0, 0.0]\nfollower_start = [[-2.0, 0.0], [2.0, 0.0]]\n"
       "[topology]\nleader_links = [1]\nedges = [[1, 2]]\n"
       "[leader]\nplugin = \"bang_bang\"\naltitude = 2.0\ndwell = \"0.4 0.8\"\nseed = 4\n";
  t += "a_min = " + std::to_string(-leader_bound) + "\na_max = " + std::to_string(leader_bound) +
       "\n";
  t += "[formation]\nplugin = \"smc_discrete\"\nperiod = 0.05\nu_min = -1.0\nu_max = 1.0\n"
       "[formation.shape]\ntype = \"offsets\"\noffsets = [[-2.0, 0.0], [2.0, 0.0]]\n"
       "[attitude]\nplugin = \"pointmass_direct\"\n";
  return t;
}

nlohmann::json RunAndSummary(const std::string& text, const std::string& dir) {
  RunOptions options;
  options.out_dir = dir;
  options.render = false;
  const RunResult r = RunExperiment(Parse(text), options);
  EXPECT_TRUE(r.complete) << r.error;
  return nlohmann::json::parse(ReadFile(dir + "/summary.json"));
}

TEST(LeaderAccelerationTest, InsideTheBoundsMeasuredExactlyAndNoNewColumnsByDefault) {
  const std::string dir = TempDir("lacc_in") + "/run";
  const auto s = RunAndSummary(Experiment(1.0, false), dir);
  const auto& a = s["leader_acceleration"];
  EXPECT_EQ(a["bounds_source"], "formation");
  EXPECT_EQ(a["samples"], 3000);
  // bang_bang commands exactly +-1; the point mass realises it up to round-off.
  EXPECT_NEAR(a["x_max"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(a["x_min"].get<double>(), -1.0, 1e-9);
  EXPECT_EQ(a["fraction_outside"].get<double>(), 0.0);
  EXPECT_TRUE(a["first_violation_time_s"].is_null());
  EXPECT_LT(a["max_excess"].get<double>(), 1e-9);
  EXPECT_TRUE(a["assumption1_holds"].get<bool>());
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  EXPECT_EQ(csv.find("leader_a"), std::string::npos);
}

TEST(LeaderAccelerationTest, OutsideTheBoundsReportedWithFirstTimeAndColumns) {
  const std::string dir = TempDir("lacc_out") + "/run";
  const auto s = RunAndSummary(Experiment(1.5, true), dir);
  const auto& a = s["leader_acceleration"];
  EXPECT_NEAR(a["x_max"].get<double>(), 1.5, 1e-9);
  EXPECT_FALSE(a["assumption1_holds"].get<bool>());
  // bang_bang is always at +-1.5: every step is outside [-1, 1], from the first one.
  EXPECT_EQ(a["fraction_outside"].get<double>(), 1.0);
  EXPECT_EQ(a["first_violation_time_s"].get<double>(), 0.0);
  EXPECT_NEAR(a["max_excess"].get<double>(), 0.5, 1e-9);
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_THAT(header, ::testing::EndsWith(",leader_ax,leader_ay"));
  // Row at t = 0.01: the acceleration over the step before it, +-1.5 on each axis.
  const size_t row = csv.find("\n0.010000,");
  ASSERT_NE(row, std::string::npos);
  const std::string line = csv.substr(row + 1, csv.find('\n', row + 1) - row - 1);
  const std::string last = line.substr(line.find_last_of(',') + 1);
  EXPECT_NEAR(std::abs(std::stod(last)), 1.5, 1e-9) << line;
}

TEST(LeaderAccelerationTest, BadLeaderInputRefusedWithFileLineAndKey) {
  std::string text = Experiment(1.0, false);
  text.replace(text.find("dwell = \"0.4 0.8\""), 17, "dwell = \"0 0.8\"");
  try {
    Parse(text);
    RunExperiment(Parse(text), {});
    ADD_FAILURE() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_THAT(e.what(), HasSubstr("exp.toml:"));
    EXPECT_THAT(e.what(), HasSubstr("[leader]"));
    EXPECT_THAT(e.what(), HasSubstr("dwell"));
  }
}

// Every experiment of experiments/leaders/ loads and creates its plugins (run from the source
// folder: the trajectory leader's CSV path is relative to it).
TEST(LeaderAccelerationTest, EveryLeaderExperimentIsAccepted) {
  const std::string folder = std::string(MJF_SOURCE_DIR) + "/experiments/leaders";
  std::vector<std::string> files;
  if (DIR* d = opendir(folder.c_str())) {
    while (dirent* e = readdir(d)) {
      const std::string name = e->d_name;
      if (name.size() > 5 && name.substr(name.size() - 5) == ".toml") files.push_back(name);
    }
    closedir(d);
  }
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 20u);
  char cwd[4096];
  ASSERT_NE(getcwd(cwd, sizeof(cwd)), nullptr);
  ASSERT_EQ(chdir(MJF_SOURCE_DIR), 0);
  for (const auto& f : files) {
    try {
      Simulation sim(LoadExperiment(folder + "/" + f));
      EXPECT_TRUE(sim.config().record_leader_acceleration) << f;
    } catch (const std::exception& e) {
      ADD_FAILURE() << f << ": " << e.what();
    }
  }
  ASSERT_EQ(chdir(cwd), 0);
}

}  // namespace
}  // namespace mjf::runner
