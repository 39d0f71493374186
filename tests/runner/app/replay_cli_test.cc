// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// runner/app/src/replay_cli.cc: `mjformation replay` without a window (PNGs of a recorded run at
// the times asked, named by the recorded time), its errors, and `view` without arguments.
#include <gtest/gtest.h>

#include <filesystem>

#include "mjformation/config/paths.hpp"
#include "mjformation/run/run.hpp"
#include "point_mass_util.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::Cli;
using mjf::testing::HoverExperiment;
using mjf::testing::Parse;
using mjf::testing::PointMassExperiment;
using mjf::testing::TempDir;

TEST(ReplayCliTest, SnapshotsOfARecordedRunAtTheNearestRecordedTimes) {
  const std::string base = TempDir("replay_cli");
  RunOptions o;
  o.out_dir = base + "/run";
  o.render = false;
  const std::string small = "[render]\nwidth = 64\nheight = 48\n";
  ASSERT_TRUE(RunExperiment(Parse(HoverExperiment(1, 0.05) + small), o).complete);
  // 0.024 s is nearest to the row of 0.02 s (rows every 0.01 s).
  ASSERT_EQ(Cli({"replay", o.out_dir, "--snapshots", "0.024", "0.05", "--out", base + "/png"}), 0);
  for (const char* name : {"replay_t000.02.png", "replay_t000.05.png"}) {
    const std::string path = base + "/png/" + name;
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    int w = 0, h = 0;
    const auto rgb = mjf::testing::ReadPng(path, &w, &h);
    EXPECT_EQ(w, 64);
    EXPECT_EQ(h, 48);
    EXPECT_EQ(rgb.size(), 64u * 48u * 3u);
  }
}

// Replay poses each vehicle by its free joint; the point-mass model moves on three slide joints,
// so its runs cannot be replayed. Refused with the scene named (exit 1), not a crash.
TEST(ReplayCliTest, APointMassRunIsReplayed) {
  const std::string base = TempDir("replay_cli_pm");
  RunOptions o;
  o.out_dir = base + "/run";
  o.render = false;
  ASSERT_TRUE(RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), o).complete);
  EXPECT_EQ(Cli({"replay", o.out_dir, "--snapshots", "0.01", "--out", base + "/png"}), 0);
  EXPECT_TRUE(std::filesystem::exists(base + "/png/replay_t000.01.png"));
}

TEST(ReplayCliTest, ASceneWithoutTheVehicleBodyIsRefusedByName) {
  const std::string base = TempDir("replay_cli_nobody");
  RunOptions o;
  o.out_dir = base + "/run";
  o.render = false;
  ASSERT_TRUE(RunExperiment(Parse(PointMassExperiment(-2, 1, 2, 1, 0.02)), o).complete);
  // The scene of another model: no vehicle bodies at all.
  mjf::testing::WriteFile(o.out_dir + "/scene.xml", "<mujoco><worldbody/></mujoco>");
  EXPECT_EQ(Cli({"replay", o.out_dir, "--snapshots", "0.01", "--out", base + "/png"}), 1);
  EXPECT_FALSE(std::filesystem::exists(base + "/png/replay_t000.01.png"));
}

TEST(ReplayCliTest, AMissingRunDirectoryIsBadInput) {
  const std::string base = TempDir("replay_cli_missing");
  EXPECT_EQ(Cli({"replay", base + "/nothing", "--snapshots", "1.0"}), 1);
  EXPECT_FALSE(std::filesystem::exists(base + "/nothing"));
}

TEST(ReplayCliTest, WindowsNeedTheViewerExecutable) {
  // The viewer is looked for next to the running executable; this test binary has none, so
  // the command says so and fails instead of starting anything.
  if (IsFile(ExecutableDir() + "/mjformation-view")) GTEST_SKIP() << "a viewer sits here";
  const std::string base = TempDir("replay_cli_view");
  EXPECT_EQ(Cli({"replay", base}), 1);
  EXPECT_EQ(Cli({"view"}), 2);  // usage
}

}  // namespace
}  // namespace mjf::runner
