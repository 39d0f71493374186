// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/src/run.cc: one run end to end: an interrupt ends it cleanly with summary.json saying
// so; no run directory means nothing written; the version string.
#include "mjformation/runner/run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <csignal>
#include <filesystem>

#include "mjformation/runner/interrupt.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using mjf::testing::ReadFile;
using mjf::testing::TempDir;
using ::testing::HasSubstr;

RunOptions Quiet(const std::string& dir) {
  RunOptions o;
  o.out_dir = dir;
  o.render = false;
  return o;
}

TEST(RunExperimentTest, AnInterruptBeforeTheFirstStepEndsTheRunCleanly) {
  const std::string dir = TempDir("run_int") + "/run";
  RequestInterrupt(SIGTERM);
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)), Quiet(dir));
  ClearInterrupt();
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.signal, SIGTERM);
  EXPECT_EQ(r.error, "interrupted by SIGTERM");
  EXPECT_EQ(r.steps, 0);
  EXPECT_EQ(r.sim_time_s, 0.0);
  const auto s = nlohmann::json::parse(ReadFile(dir + "/summary.json"));
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["interrupted_by_signal"], SIGTERM);
  EXPECT_EQ(s["error"], "interrupted by SIGTERM");
  // Everything before the loop is there: the config echo, the scene, the CSV header.
  EXPECT_TRUE(std::filesystem::exists(dir + "/config.toml"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/scene.xml"));
  const std::string csv = ReadFile(dir + "/timeseries.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1);
}

TEST(RunExperimentTest, SigintIsNamedToo) {
  RequestInterrupt(SIGINT);
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.05)), RunOptions{});
  ClearInterrupt();
  EXPECT_EQ(r.error, "interrupted by SIGINT");
  EXPECT_EQ(r.summary["interrupted_by_signal"], SIGINT);
}

TEST(RunExperimentTest, WithoutARunDirectoryNothingIsWrittenAndTheSummaryIsReturned) {
  const std::string cwd = TempDir("run_nodir");
  const auto before = std::distance(std::filesystem::directory_iterator(cwd),
                                    std::filesystem::directory_iterator());
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), RunOptions{});
  EXPECT_TRUE(r.complete) << r.error;
  EXPECT_EQ(r.steps, 20);
  EXPECT_DOUBLE_EQ(r.sim_time_s, 0.02);
  EXPECT_EQ(r.summary["complete"], true);
  EXPECT_EQ(r.summary["steps"], 20);
  // Metrics are still computed (sigma_f of the start, 1 record tick every 10 steps + the last).
  EXPECT_EQ(r.summary["metrics"]["sigma_f_samples"], 3);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(cwd),
                          std::filesystem::directory_iterator()),
            before);
}

TEST(RunExperimentTest, TheSummaryOnDiskIsTheReturnedOne) {
  const std::string dir = TempDir("run_same") + "/run";
  const RunResult r = RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), Quiet(dir));
  ASSERT_TRUE(r.complete) << r.error;
  EXPECT_EQ(ReadFile(dir + "/summary.json"), r.summary.dump(2) + "\n");
  EXPECT_GT(r.wall_time_s, 0.0);
  EXPECT_EQ(r.summary_error, "");
}

TEST(RunExperimentTest, VersionString) {
  EXPECT_THAT(VersionString(),
              ::testing::MatchesRegex("mjformation [0-9]+\\.[0-9]+\\.[0-9]+ \\(MuJoCo .*, plugin "
                                      "ABI [0-9]+\\)"));
  EXPECT_THAT(VersionString(), HasSubstr(std::string("MuJoCo ") + mj_versionString()));
  EXPECT_THAT(VersionString(), HasSubstr("plugin ABI " + std::to_string(MJF_ABI_VERSION)));
}

}  // namespace
}  // namespace mjf::runner
