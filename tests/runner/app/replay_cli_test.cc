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

// A recorded run for the tests below: 0.05 s of hovering at rows every 0.01 s, small frames.
std::string RecordedRun(const std::string& base) {
  RunOptions o;
  o.out_dir = base + "/run";
  o.render = false;
  const std::string small = "[render]\nwidth = 64\nheight = 48\n";
  EXPECT_TRUE(RunExperiment(Parse(HoverExperiment(1, 0.05) + small), o).complete);
  return o.out_dir;
}

// Nothing of the user's is replaced: replay has no --overwrite, so a --video file that exists
// is refused (exit 1) with its bytes kept, and so is a snapshot PNG of the same name; the other
// snapshots asked for are not written either (the refusal comes before any rendering).
TEST(ReplayCliTest, AnExistingVideoOrSnapshotFileOfTheUserIsNeverReplaced) {
  const std::string base = TempDir("replay_cli_keep");
  const std::string run = RecordedRun(base);
  const std::string video = base + "/mine.mp4";
  mjf::testing::WriteFile(video, "the user's video");
  EXPECT_EQ(Cli({"replay", run, "--video", video}), 1);
  EXPECT_EQ(mjf::testing::ReadFile(video), "the user's video");

  std::filesystem::create_directories(base + "/png");
  mjf::testing::WriteFile(base + "/png/replay_t000.02.png", "the user's picture");
  EXPECT_EQ(Cli({"replay", run, "--snapshots", "0.01,0.02", "--out", base + "/png"}), 1);
  EXPECT_EQ(mjf::testing::ReadFile(base + "/png/replay_t000.02.png"), "the user's picture");
  EXPECT_FALSE(std::filesystem::exists(base + "/png/replay_t000.01.png"));
  // Into the same folder, a name it does not hold yet: written beside the user's file.
  EXPECT_EQ(Cli({"replay", run, "--snapshots", "0.03", "--out", base + "/png"}), 0);
  EXPECT_TRUE(std::filesystem::exists(base + "/png/replay_t000.03.png"));
  EXPECT_EQ(mjf::testing::ReadFile(base + "/png/replay_t000.02.png"), "the user's picture");
}

// --snapshots times are checked against the recorded rows themselves: a killed run has no
// summary.json, and a time past its last row is refused, not drawn as the last frame.
TEST(ReplayCliTest, SnapshotTimesOutsideTheRecordingAreRefusedWithoutASummary) {
  const std::string base = TempDir("replay_cli_killed");
  const std::string run = RecordedRun(base);
  std::filesystem::remove(run + "/summary.json");  // as a killed run leaves it
  EXPECT_EQ(Cli({"replay", run, "--snapshots", "50", "--out", base + "/png"}), 1);
  EXPECT_FALSE(std::filesystem::exists(base + "/png"));
  EXPECT_EQ(Cli({"replay", run, "--snapshots", "-0.01", "--out", base + "/png"}), 1);
  EXPECT_EQ(Cli({"replay", run, "--snapshots", "0.05", "--out", base + "/png"}), 0);
  EXPECT_TRUE(std::filesystem::exists(base + "/png/replay_t000.05.png"));
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
