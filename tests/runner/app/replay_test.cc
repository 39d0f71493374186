// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// `mjformation replay`: a run directory rendered again from timeseries.csv and scene.xml alone
// shows the vehicles where the run's own snapshots showed them at the same times.
#include "mjformation/app/replay.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <string>

#include "mjformation/config/config.hpp"
#include "mjformation/run/run.hpp"
#include "test_util.hpp"

namespace mjf::runner {
namespace {

using mjf::testing::ReadPng;

// Fraction of pixels whose largest channel difference exceeds 25 of 255.
double DifferentPixels(const std::string& a_path, const std::string& b_path) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  const auto a = ReadPng(a_path, &wa, &ha), b = ReadPng(b_path, &wb, &hb);
  EXPECT_FALSE(a.empty()) << a_path;
  EXPECT_EQ(a.size(), b.size()) << a_path << " vs " << b_path;
  if (a.empty() || a.size() != b.size()) return 1.0;
  size_t differ = 0;
  for (size_t p = 0; p < a.size(); p += 3) {
    int d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(a[p + k]) - int(b[p + k])));
    differ += d > 25;
  }
  return static_cast<double>(differ) / (a.size() / 3);
}

class ReplayTest : public ::testing::Test {
 protected:
  // Exp 2 for 8 s (the followers sweep across the picture), snapshots at 0, 4 and 8 s.
  static void SetUpTestSuite() {
    run_dir_ = new std::string(mjf::testing::TempDir("replay") + "/run");
    const ExperimentConfig c = LoadExperiment(
        std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
        {"run.duration=8.0", "run.metric_window=[5.0, 8.0]", "render.snapshots=[0.0, 4.0, 8.0]",
         "render.width=640", "render.height=360", "render.video_width=320",
         "render.video_height=240", "render.video_fps=5.0"});
    RunOptions o;
    o.out_dir = *run_dir_;
    const RunResult r = RunExperiment(c, o);
    ASSERT_TRUE(r.complete) << r.error;
  }
  static void TearDownTestSuite() { delete run_dir_; }
  static std::string* run_dir_;
};
std::string* ReplayTest::run_dir_ = nullptr;

TEST_F(ReplayTest, RendersTheSnapshotsPositionsAtTheSameTimes) {
  const Recording rec = LoadRecording(*run_dir_);
  EXPECT_EQ(rec.n_vehicles, 7);
  EXPECT_EQ(rec.name, "exp2");
  const auto written = RenderReplay(rec, {0.0, 4.0, 8.0}, *run_dir_ + "/replay", "");
  ASSERT_EQ(written.size(), 3u);
  const char* const times[] = {"000.00", "004.00", "008.00"};
  for (const char* t : times) {
    const std::string snap = *run_dir_ + "/snapshots/t" + t + ".png";
    const std::string replay = *run_dir_ + "/replay/replay_t" + t + ".png";
    // Measured: at most 1 pixel in 10^6 differs (the CSV keeps 9 significant digits).
    EXPECT_LT(DifferentPixels(snap, replay), 1e-4) << t;
  }
  // Control: the same comparison across different times sees the vehicles elsewhere.
  EXPECT_GT(DifferentPixels(*run_dir_ + "/snapshots/t004.00.png",
                            *run_dir_ + "/replay/replay_t008.00.png"),
            0.01);
}

TEST_F(ReplayTest, WritesAVideo) {
  const Recording rec = LoadRecording(*run_dir_);
  const std::string video = *run_dir_ + "/replay.mp4";
  RenderReplay(rec, {}, "", video);
  struct stat st;
  ASSERT_EQ(stat(video.c_str(), &st), 0);
  EXPECT_GT(st.st_size, 10000);
}

// The point mass moves on three slide joints, not a free joint: replay poses those.
TEST(PointMassReplayTest, RendersTheSnapshotsPositionsAtTheSameTimes) {
  const std::string dir = mjf::testing::TempDir("replay_pm") + "/run";
  const ExperimentConfig c =
      LoadExperiment(std::string(MJF_SOURCE_DIR) + "/experiments/exp2.toml",
                     {"vehicles.model=\"pointmass\"", "attitude={plugin=\"pointmass_direct\"}",
                      "run.duration=6.0", "run.metric_window=[4.0, 6.0]",
                      "render.snapshots=[2.0, 6.0]", "render.width=640", "render.height=360"});
  RunOptions o;
  o.out_dir = dir;
  const RunResult r = RunExperiment(c, o);
  ASSERT_TRUE(r.complete) << r.error;
  const auto written = RenderReplay(LoadRecording(dir), {2.0, 6.0}, dir + "/replay", "");
  ASSERT_EQ(written.size(), 2u);
  for (const char* t : {"002.00", "006.00"}) {
    EXPECT_LT(DifferentPixels(dir + "/snapshots/t" + std::string(t) + ".png",
                              dir + "/replay/replay_t" + std::string(t) + ".png"),
              1e-4)
        << t;
  }
  EXPECT_GT(DifferentPixels(dir + "/snapshots/t002.00.png", dir + "/replay/replay_t006.00.png"),
            0.01);
}

TEST(ReplayErrorTest, NamesTheMissingFile) {
  const std::string dir = mjf::testing::TempDir("noreplay");
  try {
    LoadRecording(dir);
    FAIL() << "loaded an empty folder";
  } catch (const ReplayError& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/config.toml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mjf::runner
